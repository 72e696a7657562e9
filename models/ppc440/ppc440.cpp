#include "ppc440.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <fmt/format.h>

#include "models/common/clock.h"

namespace surfvp {

namespace {

// The phase signal's values: idle, waiting for an interrupt, the driver's own work, and the
// software stage's steps (sw/cpu_cost's names).
enum Phase : unsigned { kIdle, kWaiting, kDriver, kFirstStep };
const std::vector<std::string>& phase_names() {
    static const std::vector<std::string> names = {"idle",          "waiting_irq", "driver",      "check",
                                                   "interpolation", "laplacian",   "orientation", "descriptor"};
    return names;
}
unsigned phase_named(const char* name) {
    const auto& names = phase_names();
    const auto it = std::find(names.begin() + kFirstStep, names.end(), name);
    return it == names.end() ? kDriver : unsigned(it - names.begin());
}

}  // namespace

using sc_core::sc_time;

Ppc440::Ppc440(const sc_core::sc_module_name& name, const Params& params, Software software, Tracer& tracer)
    : sc_module(name),
      bus("bus"),
      mem("mem"),
      irq("irq"),
      params_(params),
      software_(std::move(software)),
      tracer_(tracer),
      line_(params.line_bytes) {
    tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_time(double(params.quantum.ps), sc_core::SC_PS));
    mem.register_invalidate_direct_mem_ptr(this, &Ppc440::invalidate_dmi);
    SC_HAS_PROCESS(Ppc440);
    SC_THREAD(run);
    tracer_.signal(waiting_, fmt::format("{}.waiting_irq", basename()));
    phase_signal_ = tracer_.timed_signal(fmt::format("{}.phase", basename()), 8, 0, phase_names());
    track_ = tracer_.track("cpu", basename());
    markers_.init(params.markers.size());
    for (size_t i = 0; i < params.markers.size(); ++i) {
        markers_[i].write(-1);
        tracer_.signal(markers_[i], "sw." + params.markers[i]);
        marker_tracks_.push_back(tracer_.track("sw", params.markers[i]));
    }
}

void Ppc440::set_phase(const sc_time& at, unsigned phase) {
    if (phase_signal_ < 0 || phase == phase_) return;
    phase_ = phase;
    tracer_.timed_change(phase_signal_, phase, at.value());
}

// The software's "idle" span (waiting for work) is idle; any other is the driver's work.
unsigned Ppc440::phase_of_spans() const { return !spans_.empty() && spans_.back().name == "idle" ? kIdle : kDriver; }

void Ppc440::split_next_compute(const std::vector<std::pair<const char*, uint64_t>>& steps) {
    if (phase_signal_ >= 0) next_split_ = steps;
}

// The steps of the split given for this compute() across its time, by their cycles (the
// stalls spread with them).
void Ppc440::trace_compute(const sc_time& start, const sc_time& end) {
    uint64_t total = 0;
    for (const auto& s : next_split_) total += s.second;
    uint64_t done = 0;
    for (const auto& [name, c] : next_split_) {
        set_phase(start + (end - start) * (double(done) / double(total)), phase_named(name));
        done += c;
    }
    set_phase(end, phase_of_spans());
    next_split_.clear();
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
    set_phase(sc_core::sc_time_stamp(), kIdle);
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
        throw sw::BusError(
            fmt::format("{} of the register at {:#010x}: {}", command == tlm::TLM_READ_COMMAND ? "read" : "write",
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

bool Ppc440::dmi_covers(uint32_t address, size_t bytes) {
    if (!dmi_valid_ || address < dmi_.get_start_address() || address + bytes - 1 > dmi_.get_end_address()) {
        tlm::tlm_generic_payload tx;
        tx.set_command(tlm::TLM_READ_COMMAND);
        tx.set_address(address);
        dmi_valid_ = mem->get_direct_mem_ptr(tx, dmi_);
        if (!dmi_valid_) return false;
    }
    return dmi_.is_read_allowed() && address >= dmi_.get_start_address() &&
           address + bytes - 1 <= dmi_.get_end_address();
}

void Ppc440::invalidate_dmi(sc_dt::uint64, sc_dt::uint64) { dmi_valid_ = false; }

// One line on the memory path, requested at time `at`, or now if the kernel has passed it (a
// synchronising path such as PLB1 waits for its grant); returns when it is done.
sc_time Ppc440::line_access(tlm::tlm_command command, uint32_t address, uint8_t* data, size_t bytes,
                            const sc_time& at) {
    tlm::tlm_generic_payload& tx = line_tx_;
    tx.set_command(command);
    tx.set_address(address);
    tx.set_data_ptr(data);
    tx.set_data_length(static_cast<unsigned>(bytes));
    tx.set_streaming_width(static_cast<unsigned>(bytes));
    tx.set_byte_enable_ptr(nullptr);
    tx.set_dmi_allowed(false);
    tx.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    sc_time delay = std::max(at, sc_core::sc_time_stamp()) - sc_core::sc_time_stamp();
    mem->b_transport(tx, delay);  // the MCI link annotates; PLB1 synchronises first
    if (!tx.is_response_ok())
        throw sw::BusError(fmt::format("memory {} at {:#010x}: {}", command == tlm::TLM_READ_COMMAND ? "read" : "write",
                                       address, tx.get_response_string()),
                           address);
    (command == tlm::TLM_READ_COMMAND ? stats_.bytes_read : stats_.bytes_written) += bytes;
    return sc_core::sc_time_stamp() + delay;
}

// A copy through the caches: line after line on the memory path, each after the one before,
// from the kernel's time (synchronised, so that the quantum does not move the traffic).
void Ppc440::memory(tlm::tlm_command command, uint32_t address, uint8_t* data, size_t bytes) {
    keeper_.sync();
    sc_time at = sc_core::sc_time_stamp();
    for (size_t done = 0; done < bytes;) {
        const size_t n = std::min<size_t>(params_.line_bytes - (address + done) % params_.line_bytes, bytes - done);
        at = line_access(command, uint32_t(address + done), data + done, n, at);
        done += n;
    }
    at = std::max(at, sc_core::sc_time_stamp());
    keeper_.set(at - sc_core::sc_time_stamp());
    if (keeper_.need_sync()) keeper_.sync();
}

void Ppc440::read(uint32_t address, void* data, size_t bytes) {
    memory(tlm::TLM_READ_COMMAND, address, static_cast<uint8_t*>(data), bytes);
}

void Ppc440::write(uint32_t address, const void* data, size_t bytes) {
    // A write command only reads through the payload's pointer.
    memory(tlm::TLM_WRITE_COMMAND, address, static_cast<uint8_t*>(const_cast<void*>(data)), bytes);
}

const uint8_t* Ppc440::map(uint32_t address, size_t bytes) {
    if (bytes == 0 || !dmi_covers(address, bytes))
        throw sw::BusError(fmt::format("no direct memory at {:#010x} (+{} B)", address, bytes), address);
    return dmi_.get_dmi_ptr() + (address - dmi_.get_start_address());
}

// The fills asked at the same cycle of work, from lines[i] on (a burst: loads issued before
// any of them is used): each takes a free fill slot (waiting for the oldest outstanding fill
// when all are taken) and is asked at its own time; returns when the CPU has the data of all
// of them (their critical words, or whole lines).
sc_time Ppc440::fill_burst(const std::vector<sw::LineTransfer>& lines, size_t& i, sc_time at) {
    const sc_time lead(double(params_.critical_word_lead.ps), sc_core::SC_PS);
    sc_time data = at;
    const uint64_t cycle = lines[i].at_cycle;
    for (; i < lines.size() && !lines[i].write_back && lines[i].at_cycle == cycle; ++i) {
        in_flight_.erase(
            std::remove_if(in_flight_.begin(), in_flight_.end(), [&](const sc_time& t) { return t <= at; }),
            in_flight_.end());
        if (in_flight_.size() >= params_.outstanding_fills) {
            const auto oldest = std::min_element(in_flight_.begin(), in_flight_.end());
            at = *oldest;
            in_flight_.erase(oldest);
            ++stats_.fill_slot_waits;
        }
        const sc_time line = line_access(tlm::TLM_READ_COMMAND, lines[i].address, line_.data(), line_.size(), at);
        in_flight_.push_back(line);
        data = std::max(data, std::max(at, line - lead));
        ++stats_.fills;
    }
    return std::max(data, at);
}

// The step starts at the kernel's time (synchronised) and hands each line to the memory path
// with its own time; the memory path reaches the DRAM in the kernel at that time, so the
// fills meet the other masters' traffic in request order whatever the quantum. A write-back carries the line's current contents (the
// model keeps no dirty data of its own, so memory is unchanged); it is posted over the MCI
// link, while over PLB1 (a synchronising bus) the CPU waits for its grant.
uint64_t Ppc440::compute(uint64_t count, const std::vector<sw::LineTransfer>& lines, uint64_t untimed_fills) {
    if (untimed_fills) throw std::logic_error("cpu: every line fill is timed here: give it as a line");
    keeper_.sync();
    const sc_time start = sc_core::sc_time_stamp();
    if (!next_split_.empty()) set_phase(start, phase_named(next_split_.front().first));
    sc_time at = start;  // where the step has got to
    uint64_t done = 0;   // cycles of work so far
    for (size_t i = 0; i < lines.size();) {
        const sw::LineTransfer& line = lines[i];
        const uint64_t cycle = std::min(std::max(line.at_cycle, done), count);
        at += cycles(params_.clock, double(cycle - done));
        done = cycle;
        if (line.write_back) {
            if (dmi_covers(line.address, line_.size()))
                std::memcpy(line_.data(), map(line.address, line_.size()), line_.size());
            line_access(tlm::TLM_WRITE_COMMAND, line.address, line_.data(), line_.size(), at);
            at = std::max(at, sc_core::sc_time_stamp());
            ++stats_.write_backs;
            ++i;
        } else {
            const sc_time data = fill_burst(lines, i, at);
            stats_.fill_stall += data - at;
            at = data;
        }
    }
    at = std::max(at, sc_core::sc_time_stamp()) + cycles(params_.clock, double(count - done));
    stats_.cycles_consumed += count;
    keeper_.set(at - sc_core::sc_time_stamp());
    if (!next_split_.empty()) trace_compute(start, at);
    if (keeper_.need_sync()) keeper_.sync();
    return uint64_t(std::llround((at - start).to_seconds() * params_.clock.hz));
}

bool Ppc440::irq_pending() {
    keeper_.sync();  // the input's level at the software's own time
    if (irq.read()) take_irq_flows();
    return irq.read();
}

uint64_t Ppc440::time_ps() { return now().value(); }

bool Ppc440::wait_for_irq(uint64_t timeout_ps) {
    keeper_.sync();
    ++stats_.irq_waits;
    if (irq.read()) {
        take_irq_flows();
        return true;
    }
    const sc_time began = sc_core::sc_time_stamp();
    waiting_.write(true);
    set_phase(began, kWaiting);
    if (timeout_ps == kNoTimeout)
        sc_core::wait(irq.posedge_event());
    else
        sc_core::wait(sc_time(double(timeout_ps), sc_core::SC_PS), irq.posedge_event());
    waiting_.write(false);
    stats_.irq_wait_time += sc_core::sc_time_stamp() - began;
    set_phase(sc_core::sc_time_stamp(), phase_of_spans());
    if (tracer_.perfetto_on()) tracer_.slice(track_, "wait for irq", began, sc_core::sc_time_stamp());
    if (irq.read()) take_irq_flows();
    return irq.read();
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

// The interrupts' flows (the INTC posts one at each rise) end at the next span: the handling.
void Ppc440::take_irq_flows() {
    while (const uint64_t id = tracer_.take_flow("cpu irq")) irq_flows_.push_back(id);
}

void Ppc440::begin(const char* what) {
    spans_.push_back({what, now()});
    set_phase(spans_.back().start, phase_of_spans());
    for (const uint64_t id : irq_flows_) tracer_.flow(track_, spans_.back().start, id, Tracer::Flow::end, "interrupt");
    irq_flows_.clear();
}

void Ppc440::end() {
    if (spans_.empty()) return;
    const sc_time at = now();
    if (tracer_.perfetto_on()) tracer_.slice(track_, spans_.back().name, spans_.back().start, at);
    spans_.pop_back();
    set_phase(at, phase_of_spans());
}

void Ppc440::register_statistics(const Statistics::Scope& s) const {
    s.value("clock_hz", params_.clock.hz, "Hz", "the CPU's clock");
    s.count(
        "mmio_reads", [this] { return stats_.mmio_reads; }, "accesses", "register reads over PLB1");
    s.count(
        "mmio_writes", [this] { return stats_.mmio_writes; }, "accesses", "register writes over PLB1");
    const Statistics::Scope m = s / "memory";
    m.bytes(
        "bytes_read", [this] { return stats_.bytes_read; }, "read on the memory path: copies and line fills");
    m.bytes(
        "bytes_written", [this] { return stats_.bytes_written; }, "written on the memory path: copies and write-backs");
    m.count(
        "line_fills", [this] { return stats_.fills; }, "lines", "L1 line fills");
    m.count(
        "write_backs", [this] { return stats_.write_backs; }, "lines", "L1 write-backs");
    m.time(
        "fill_stall_s", [this] { return stats_.fill_stall; }, "the CPU waiting for its line fills");
    m.count(
        "fill_slot_waits", [this] { return stats_.fill_slot_waits; }, "fills",
        "fills that waited for one of the outstanding ones to finish");
    s.count(
        "cycles_consumed", [this] { return stats_.cycles_consumed; }, "cycles", "work, without the stalls");
    s.count(
        "irq_waits", [this] { return stats_.irq_waits; }, "waits", "times the software slept on the interrupt");
    s.time(
        "irq_wait_s", [this] { return stats_.irq_wait_time; }, "asleep on the interrupt");
}

}  // namespace surfvp
