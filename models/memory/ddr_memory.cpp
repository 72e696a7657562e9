#include "ddr_memory.h"

#include <algorithm>
#include <cstring>
#include <fmt/format.h>
#include <stdexcept>

#include "models/common/clock.h"

namespace surfvp {
using sc_core::sc_time;

DdrMemory::DdrMemory(const sc_core::sc_module_name& name, const Params& params)
    : sc_module(name),
      ports("ports"),
      params_(params),
      bytes_per_second_(bytes_per_second(params)),
      read_latency_(cycles(params.clock, params.latency_cycles)),
      write_latency_(cycles(params.clock, params.write_latency_cycles)),
      series_(params.series_bin.ps) {
    if (params.size.n == 0) throw std::invalid_argument(fmt::format("{}: memory size must be above zero", basename()));
    if (params.efficiency <= 0 || params.efficiency > 1)
        throw std::invalid_argument(
            fmt::format("{}: efficiency must be in (0, 1], not {}", basename(), params.efficiency));
    storage_ = zeroed_memory(params.size.n, std::string("the modelled DDR memory (") + basename() + ", memory.size)");
    if (params.populate_ahead) populate_ = std::make_unique<PopulateAhead>(storage_.get(), params.size.n);
    ports.register_b_transport(this, &DdrMemory::b_transport);
    ports.register_get_direct_mem_ptr(this, &DdrMemory::get_direct_mem_ptr);
    ports.register_transport_dbg(this, &DdrMemory::transport_dbg);
}

DdrMemory::~DdrMemory() {
    populate_.reset();  // it waits for the pages it asked for
    release_in_background(std::move(storage_));
}

void DdrMemory::name_port(const std::string& name) {
    port_stats_.emplace_back();
    port_stats_.back().name = name;
}

DdrMemory::PortStats& DdrMemory::stats(int port) {
    while (port_stats_.size() <= static_cast<size_t>(port)) name_port(fmt::format("port{}", port_stats_.size()));
    return port_stats_[port];
}

sc_time DdrMemory::latency() const { return read_latency_; }

double DdrMemory::bytes_per_second(const Params& p) {
    return p.width_bits / 8.0 * p.transfers_per_clock * p.clock.hz * p.efficiency;
}

double DdrMemory::bytes_per_second() const { return bytes_per_second_; }

sc_time DdrMemory::read_time(const Params& p, uint64_t bytes) {
    return cycles(p.clock, p.latency_cycles) + transfer_time(bytes, bytes_per_second(p));
}

uint8_t* DdrMemory::backdoor(uint64_t address, uint64_t bytes) {
    if (address + bytes > params_.size.n)
        throw std::out_of_range(fmt::format("{}: [{:#x}, +{}) is outside the memory", basename(), address, bytes));
    return storage_.get() + address;
}

bool DdrMemory::check(tlm::tlm_generic_payload& tx) const {
    if (tx.get_address() + tx.get_data_length() > params_.size.n) {
        tx.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
        return false;
    }
    if (tx.get_byte_enable_ptr() != nullptr) {
        tx.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
        return false;
    }
    if (tx.get_streaming_width() < tx.get_data_length()) {
        tx.set_response_status(tlm::TLM_BURST_ERROR_RESPONSE);
        return false;
    }
    return true;
}

void DdrMemory::b_transport(int port, tlm::tlm_generic_payload& tx, sc_time& delay) {
    if (!check(tx)) return;
    uint8_t* cell = storage_.get() + tx.get_address();
    const uint64_t bytes = tx.get_data_length();
    PortStats& s = stats(port);
    if (tx.is_write()) {
        if (populate_) populate_->writing(tx.get_address(), bytes);
        std::memcpy(cell, tx.get_data_ptr(), bytes);
        ++s.writes;
        s.bytes_written += bytes;
    } else if (tx.is_read()) {
        std::memcpy(tx.get_data_ptr(), cell, bytes);
        ++s.reads;
        s.bytes_read += bytes;
    }
    const sc_time now = sc_core::sc_time_stamp();
    const sc_time request = now + delay;
    const sc_time transfer = transfer_time(bytes, bytes_per_second_);
    dram_.forget_before(now.value());
    const sc_time start = sc_time::from_value(dram_.reserve(request.value(), transfer.value()));
    busy_ += transfer;
    series_.busy(start.value(), (start + transfer).value());
    s.wait += start - request;
    delay += (start - request) + (tx.is_write() ? write_latency_ : read_latency_) + transfer;
    tx.set_response_status(tlm::TLM_OK_RESPONSE);
}

bool DdrMemory::get_direct_mem_ptr(int, tlm::tlm_generic_payload& tx, tlm::tlm_dmi& dmi) {
    dmi.set_dmi_ptr(storage_.get());
    dmi.set_start_address(0);
    dmi.set_end_address(params_.size.n - 1);
    dmi.allow_read_write();
    dmi.set_read_latency(latency());
    dmi.set_write_latency(write_latency_);
    return tx.get_address() < params_.size.n;
}

unsigned DdrMemory::transport_dbg(int, tlm::tlm_generic_payload& tx) {
    const uint64_t address = tx.get_address();
    if (address >= params_.size.n) return 0;
    const auto n = static_cast<unsigned>(std::min<uint64_t>(tx.get_data_length(), params_.size.n - address));
    if (tx.is_write())
        std::memcpy(storage_.get() + address, tx.get_data_ptr(), n);
    else if (tx.is_read())
        std::memcpy(tx.get_data_ptr(), storage_.get() + address, n);
    return n;
}

void DdrMemory::register_statistics(const Statistics::Scope& s) const {
    auto total = [this](uint64_t PortStats::*field) {
        return [this, field] {
            uint64_t sum = 0;
            for (const PortStats& p : port_stats_) sum += p.*field;
            return sum;
        };
    };
    s.bytes("bytes_read", total(&PortStats::bytes_read), "bytes read, all ports");
    s.bytes("bytes_written", total(&PortStats::bytes_written), "bytes written, all ports");
    s.time(
        "busy_s", [this] { return busy_; }, "the DRAM transferring data");
    s.share(
        "utilisation", [this] { return busy_; }, "busy over the run");
    s.series("busy_series", series_, "share", "busy share per time bin");
    for (size_t i = 0; i < port_stats_.size(); ++i) {
        const Statistics::Scope p = s / "ports" / port_stats_[i].name;
        p.count(
            "reads", [this, i] { return port_stats_[i].reads; }, "accesses", "reads on this port");
        p.count(
            "writes", [this, i] { return port_stats_[i].writes; }, "accesses", "writes on this port");
        p.bytes(
            "bytes_read", [this, i] { return port_stats_[i].bytes_read; }, "bytes read on this port");
        p.bytes(
            "bytes_written", [this, i] { return port_stats_[i].bytes_written; }, "bytes written on this port");
        p.time(
            "wait_s", [this, i] { return port_stats_[i].wait; }, "waiting for the DRAM behind other accesses");
    }
}

}  // namespace surfvp
