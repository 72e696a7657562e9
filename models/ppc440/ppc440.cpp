#include "ppc440.h"

#include <algorithm>
#include <cstring>
#include <fmt/format.h>

#include "models/common/clock.h"
#include "models/common/dmi_rate.h"

namespace surfvp {
using sc_core::sc_time;

Ppc440::Ppc440(const sc_core::sc_module_name& name, const Params& params, Software software, Tracer& tracer)
    : sc_module(name), bus("bus"), irq("irq"), params_(params), software_(std::move(software)), tracer_(tracer) {
    tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(double(params.quantum.ps), sc_core::SC_PS));
    bus.register_invalidate_direct_mem_ptr(this, &Ppc440::invalidate_dmi);
    SC_HAS_PROCESS(Ppc440);
    SC_THREAD(run);
    tracer_.signal(waiting_, fmt::format("{}.waiting_irq", basename()));
    track_ = tracer_.track("cpu", basename());
    markers_.init(params.markers.size());
    for (size_t i = 0; i < params.markers.size(); ++i) {
        markers_[i].write(-1);
        tracer_.signal(markers_[i], "sw." + params.markers[i]);
        marker_tracks_.push_back(tracer_.track("sw", params.markers[i]));
    }
}

sc_time Ppc440::now() const { return sc_core::sc_time_stamp() + keeper_.get_local_time(); }

void Ppc440::run() {
    keeper_.reset();
    try {
        software_(*this);
    } catch (const sw::BusError& e) {
        error_ = fmt::format("bus error at {:#010x}: {}", e.address, e.what());
    } catch (const std::exception& e) {
        error_ = e.what();
    }
    while (!spans_.empty()) end();
    keeper_.sync();
    finished_ = true;
    finish_time_ = sc_core::sc_time_stamp();
    done_.notify();
}

void Ppc440::mmio(tlm::tlm_command command, uint32_t address, uint8_t* data) {
    tlm::tlm_generic_payload tx;
    tx.set_command(command);
    tx.set_address(address);
    tx.set_data_ptr(data);
    tx.set_data_length(4);
    tx.set_streaming_width(4);
    tx.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    sc_time delay = keeper_.get_local_time();
    bus->b_transport(tx, delay);
    keeper_.set(delay);
    if (keeper_.need_sync()) keeper_.sync();
    if (!tx.is_response_ok())
        throw sw::BusError(fmt::format("{} of the register at {:#010x}: {}", command == tlm::TLM_READ_COMMAND ? "read" : "write",
                                       address, tx.get_response_string()),
                           address);
}

uint32_t Ppc440::read32(uint32_t address) {
    uint8_t data[4] = {};
    mmio(tlm::TLM_READ_COMMAND, address, data);
    ++stats_.mmio_reads;
    return load_be32(data);
}

void Ppc440::write32(uint32_t address, uint32_t value) {
    uint8_t data[4];
    store_be32(data, value);
    mmio(tlm::TLM_WRITE_COMMAND, address, data);
    ++stats_.mmio_writes;
}

bool Ppc440::dmi_covers(uint32_t address, size_t bytes, tlm::tlm_command command) {
    if (!dmi_valid_ || address < dmi_.get_start_address() || address + bytes - 1 > dmi_.get_end_address()) {
        tlm::tlm_generic_payload tx;
        DmiRate rate;
        tx.set_command(command);
        tx.set_address(address);
        tx.set_extension(&rate);
        dmi_valid_ = bus->get_direct_mem_ptr(tx, dmi_);
        tx.clear_extension(&rate);
        dmi_rate_ = rate.bytes_per_second;
        if (!dmi_valid_) return false;
    }
    const bool allowed = command == tlm::TLM_READ_COMMAND ? dmi_.is_read_allowed() : dmi_.is_write_allowed();
    return allowed && address >= dmi_.get_start_address() && address + bytes - 1 <= dmi_.get_end_address();
}

void Ppc440::invalidate_dmi(sc_dt::uint64, sc_dt::uint64) { dmi_valid_ = false; }

void Ppc440::memory(tlm::tlm_command command, uint32_t address, uint8_t* data, size_t bytes) {
    if (bytes == 0) return;
    if (dmi_covers(address, bytes, command)) {
        uint8_t* cell = dmi_.get_dmi_ptr() + (address - dmi_.get_start_address());
        if (command == tlm::TLM_READ_COMMAND) std::memcpy(data, cell, bytes);
        else std::memcpy(cell, data, bytes);
        const sc_time latency = command == tlm::TLM_READ_COMMAND ? dmi_.get_read_latency() : dmi_.get_write_latency();
        keeper_.inc(latency + transfer_time(bytes, dmi_rate_));
        if (keeper_.need_sync()) keeper_.sync();
        return;
    }
    // No DMI here: one bus transaction per cache line.
    for (size_t done = 0; done < bytes;) {
        const size_t n = std::min<size_t>(params_.line_bytes, bytes - done);
        tlm::tlm_generic_payload tx;
        tx.set_command(command);
        tx.set_address(address + done);
        tx.set_data_ptr(data + done);
        tx.set_data_length(static_cast<unsigned>(n));
        tx.set_streaming_width(static_cast<unsigned>(n));
        tx.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
        sc_time delay = keeper_.get_local_time();
        bus->b_transport(tx, delay);
        keeper_.set(delay);
        if (!tx.is_response_ok())
            throw sw::BusError(fmt::format("memory {} at {:#010x}: {}", command == tlm::TLM_READ_COMMAND ? "read" : "write",
                                           address + done, tx.get_response_string()),
                               static_cast<uint32_t>(address + done));
        done += n;
    }
    if (keeper_.need_sync()) keeper_.sync();
}

void Ppc440::read(uint32_t address, void* data, size_t bytes) {
    memory(tlm::TLM_READ_COMMAND, address, static_cast<uint8_t*>(data), bytes);
    stats_.bytes_read += bytes;
}

void Ppc440::write(uint32_t address, const void* data, size_t bytes) {
    // A write command only reads through the payload's pointer.
    memory(tlm::TLM_WRITE_COMMAND, address, static_cast<uint8_t*>(const_cast<void*>(data)), bytes);
    stats_.bytes_written += bytes;
}

const uint8_t* Ppc440::map(uint32_t address, size_t bytes) {
    if (bytes == 0 || !dmi_covers(address, bytes, tlm::TLM_READ_COMMAND))
        throw sw::BusError(fmt::format("no direct memory at {:#010x} (+{} B)", address, bytes), address);
    return dmi_.get_dmi_ptr() + (address - dmi_.get_start_address());
}

bool Ppc440::irq_pending() {
    keeper_.sync();  // the input's level at the software's own time
    return irq.read();
}

uint64_t Ppc440::time_ps() { return now().value(); }

void Ppc440::wait_for_irq() {
    keeper_.sync();
    ++stats_.irq_waits;
    if (irq.read()) return;
    const sc_time began = sc_core::sc_time_stamp();
    waiting_.write(true);
    sc_core::wait(irq.posedge_event());
    waiting_.write(false);
    stats_.irq_wait_time += sc_core::sc_time_stamp() - began;
    if (tracer_.perfetto_on()) tracer_.slice(track_, "wait for irq", began, sc_core::sc_time_stamp());
}

void Ppc440::consume(uint64_t count) {
    stats_.cycles_consumed += count;
    keeper_.inc(cycles(params_.clock, double(count)));
    if (keeper_.need_sync()) keeper_.sync();
}

void Ppc440::mark(unsigned index, int value) {
    if (index >= markers_.size()) return;
    keeper_.sync();  // the signal changes at the software's own time
    markers_[index].write(value);
    if (tracer_.perfetto_on())
        tracer_.counter(marker_tracks_[index], params_.markers[index], sc_core::sc_time_stamp(), value);
}

void Ppc440::begin(const char* what) { spans_.push_back({what, now()}); }

void Ppc440::end() {
    if (spans_.empty()) return;
    if (tracer_.perfetto_on()) tracer_.slice(track_, spans_.back().name, spans_.back().start, now());
    spans_.pop_back();
}

}  // namespace surfvp
