#include "mci_link.h"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

#include "models/common/clock.h"

namespace surfvp {
using sc_core::sc_time;

MciLink::MciLink(const sc_core::sc_module_name& name, const Params& params)
    : sc_module(name), cpu("cpu"), memory("memory"), params_(params) {
    if (params.width_bits == 0 || params.width_bits % 8)
        throw std::invalid_argument(fmt::format("{}: width must be a whole number of bytes", basename()));
    cpu.register_b_transport(this, &MciLink::b_transport);
    cpu.register_get_direct_mem_ptr(this, &MciLink::get_direct_mem_ptr);
    cpu.register_transport_dbg(this, &MciLink::transport_dbg);
}

namespace {
double beats(const MciLink::Params& p, uint64_t bytes) {
    const uint64_t width = p.width_bits / 8;
    return double(std::max<uint64_t>(1, (bytes + width - 1) / width));
}
}  // namespace

sc_time MciLink::access_time(const Params& p, uint64_t bytes, const sc_time& memory_time) {
    return cycles(p.clock, p.latency_cycles) + std::max(cycles(p.clock, beats(p, bytes)), memory_time);
}

sc_time MciLink::own_time(const Params& p, uint64_t bytes) {
    return cycles(p.clock, p.latency_cycles + beats(p, bytes));
}

// A read reaches the DRAM after the link's address phase; the link waits in the kernel until
// then, so that the DDR grants it and the DMA's bursts in the order they were asked (the CPU
// waits for a read's data anyway). A write is posted: the CPU goes on at once, so it is
// annotated and takes its DRAM time when handed over (the few write-backs of keypoint records).
void MciLink::b_transport(tlm::tlm_generic_payload& tx, sc_time& delay) {
    const sc_time request = sc_core::sc_time_stamp() + delay;
    const sc_time start = std::max(request, free_at_);
    const sc_time overhead = cycles(params_.clock, params_.latency_cycles);
    const sc_time own = own_time(params_, tx.get_data_length());
    free_at_ = start + own;
    if (tx.is_read() && start + overhead > sc_core::sc_time_stamp())
        sc_core::wait(start + overhead - sc_core::sc_time_stamp());
    sc_time memory_time = start + overhead - sc_core::sc_time_stamp();  // the DDR sees it after the address phase
    memory->b_transport(tx, memory_time);
    memory_time -= start + overhead - sc_core::sc_time_stamp();
    const sc_time end = start + access_time(params_, tx.get_data_length(), memory_time);
    stats_.wait += start - request;
    stats_.busy += own;
    if (tx.is_write()) {
        ++stats_.writes;
        stats_.bytes_written += tx.get_data_length();
    } else {
        ++stats_.reads;
        stats_.bytes_read += tx.get_data_length();
    }
    delay = end - sc_core::sc_time_stamp();
}

bool MciLink::get_direct_mem_ptr(tlm::tlm_generic_payload& tx, tlm::tlm_dmi& dmi) {
    return memory->get_direct_mem_ptr(tx, dmi);
}

unsigned MciLink::transport_dbg(tlm::tlm_generic_payload& tx) { return memory->transport_dbg(tx); }

void MciLink::register_statistics(const Statistics::Scope& s) const {
    s.count(
        "reads", [this] { return stats_.reads; }, "accesses", "reads");
    s.count(
        "writes", [this] { return stats_.writes; }, "accesses", "writes");
    s.bytes(
        "bytes_read", [this] { return stats_.bytes_read; }, "bytes read");
    s.bytes(
        "bytes_written", [this] { return stats_.bytes_written; }, "bytes written");
    s.time(
        "busy_s", [this] { return stats_.busy; }, "the link's own cycles: address phases and data beats");
    s.share(
        "utilisation", [this] { return stats_.busy; }, "busy over the run");
    s.time(
        "wait_s", [this] { return stats_.wait; }, "requests waiting behind earlier ones");
}

}  // namespace surfvp
