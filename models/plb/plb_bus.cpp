#include "plb_bus.h"

#include <algorithm>
#include <fmt/compile.h>
#include <fmt/format.h>
#include <stdexcept>

#include "models/common/clock.h"
#include "models/common/end_of_instant.h"

namespace surfvp {
using sc_core::sc_time;
using sc_core::SC_ZERO_TIME;

PlbBus::PlbBus(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer)
    : sc_module(name), masters("masters"), slaves("slaves"), params_(params), tracer_(tracer) {
    read_.series = write_.series = TimeSeries(params.series_bin.ps);
    if (params.width_bits != 32 && params.width_bits != 64 && params.width_bits != 128)
        throw std::invalid_argument(
            fmt::format("{}: PLB width must be 32, 64 or 128 bit, not {}", basename(), params.width_bits));
    if (params.max_burst_beats < 2 || params.max_burst_beats > 16)
        throw std::invalid_argument(
            fmt::format("{}: PLB bursts are 2 to 16 beats, not {}", basename(), params.max_burst_beats));
    masters.register_b_transport(this, &PlbBus::b_transport);
    masters.register_get_direct_mem_ptr(this, &PlbBus::get_direct_mem_ptr);
    masters.register_transport_dbg(this, &PlbBus::transport_dbg);
    slaves.register_invalidate_direct_mem_ptr(this, &PlbBus::invalidate_direct_mem_ptr);

    EndOfInstant::get();  // made during elaboration
    for (Path* path : {&read_, &write_}) {
        path->busy = std::make_unique<sc_core::sc_signal<bool, sc_core::SC_UNCHECKED_WRITERS>>(
            fmt::format("{}_busy", path->name).c_str());
        tracer_.signal(*path->busy, fmt::format("{}.{}_busy", basename(), path->name));
        path->track = tracer_.track(basename(), fmt::format("{} data", path->name));
        sc_core::sc_spawn_options options;
        options.spawn_method();
        options.dont_initialize();
        options.set_sensitivity(&path->arbitrate);
        sc_core::sc_spawn([this, path] { arbitrate(path); }, fmt::format("{}_arbiter", path->name).c_str(), &options);
    }
}

void PlbBus::connect_master(tlm::tlm_base_initiator_socket<>& socket, const std::string& name, unsigned burst_beats) {
    socket.bind(masters);
    master_burst_.push_back(burst_beats ? std::min(burst_beats, params_.max_burst_beats) : params_.max_burst_beats);
    master_stats_.emplace_back();
    master_stats_.back().name = name;
    // A master's reads and writes are in flight at once: a track each.
    master_tracks_.push_back({tracer_.track(basename(), name + " read"), tracer_.track(basename(), name + " write")});
    read_.granted.emplace_back();
    write_.granted.emplace_back();
}

void PlbBus::map(uint64_t base, uint64_t size, unsigned slave, const std::string& name) {
    for (const Route& r : routes_)
        if (base < r.base + r.size && r.base < base + size)
            throw std::invalid_argument(
                fmt::format("{}: region {} [{:#x}, +{:#x}) overlaps {}", basename(), name, base, size, r.name));
    routes_.push_back({base, size, slave, name});
}

void PlbBus::start_of_simulation() {
    if (static_cast<size_t>(masters.size()) != master_stats_.size())
        throw std::logic_error(fmt::format("{}: bind masters with connect_master()", basename()));
}

sc_time PlbBus::burst_time(const Params& p, uint64_t bytes, const sc_time& slave_time) {
    const uint64_t width_bytes = p.width_bits / 8;
    const uint64_t beats = std::max<uint64_t>(1, (bytes + width_bytes - 1) / width_bytes);
    const uint64_t bursts = (beats + p.max_burst_beats - 1) / p.max_burst_beats;
    const sc_time overhead = cycles(p.clock, double(bursts * (p.arbitration_cycles + p.address_cycles)));
    return overhead + std::max(cycles(p.clock, double(beats)), slave_time);
}

sc_time PlbBus::transaction_time(uint64_t bytes) const { return burst_time(params_, bytes, SC_ZERO_TIME); }

const PlbBus::Route* PlbBus::decode(uint64_t address, uint64_t length) const {
    for (const Route& r : routes_)
        if (address >= r.base && address - r.base + length <= r.size) return &r;
    return nullptr;
}

int PlbBus::pick(const Path& path) const {
    const int n = static_cast<int>(master_stats_.size());
    auto rank = [&](int master) {
        if (params_.arbitration == Arbitration::fixed_priority) return master;
        return (master - path.last_master - 1 + n) % n;  // the master after the last winner first
    };
    int best = 0;
    for (int i = 1; i < static_cast<int>(path.pending.size()); ++i)
        if (rank(path.pending[i].master) < rank(path.pending[best].master)) best = i;
    return best;
}

// The path's arbiter: runs after a request and when the path becomes free. It decides at the
// end of the instant (EndOfInstant), so that every request made at that time, in any delta,
// is present when the policy picks.
void PlbBus::arbitrate(Path* path) {
    const sc_time now = sc_core::sc_time_stamp();
    if (path->in_flight || path->deciding) return;  // the winner re-arms us when its end is known
    if (now < path->free_at) {
        path->arbitrate.notify(path->free_at - now);
        return;
    }
    path->deciding = true;
    EndOfInstant::get().at_end([this, path] { decide(path); });
}

void PlbBus::decide(Path* path) {
    path->deciding = false;
    if (path->in_flight || sc_core::sc_time_stamp() < path->free_at) {
        path->arbitrate.notify(SC_ZERO_TIME);
        return;
    }
    if (path->pending.empty()) {
        if (tracer_.vcd_on()) path->busy->write(false);
        return;
    }
    const int index = pick(*path);
    const int master = path->pending[index].master;
    path->pending.erase(path->pending.begin() + index);
    path->in_flight = true;
    path->last_master = master;
    if (tracer_.vcd_on()) path->busy->write(true);
    path->granted[master].notify();
}

std::string PlbBus::wait_bin_name(size_t bin) {
    if (bin == 0) return "0";
    if (bin == 1) return "1";
    if (bin == 7) return "64+";
    return std::to_string(1u << (bin - 1)) + "-" + std::to_string((1u << bin) - 1);
}

void PlbBus::record_wait(MasterStats& stats, const sc_time& wait) const {
    stats.wait += wait;
    stats.max_wait = std::max(stats.max_wait, wait);
    const uint64_t cycles = uint64_t(wait.to_seconds() * 1e12 / params_.clock.period_ps() + 1e-9);
    size_t bin = 0;
    while (bin < 7 && cycles >= (uint64_t(1) << bin)) ++bin;
    ++stats.wait_histogram[bin];
}

void PlbBus::await_grant(Path& path, int master) {
    path.pending.push_back({master, sc_core::sc_time_stamp()});
    path.arbitrate.notify(SC_ZERO_TIME);
    sc_core::wait(path.granted[master]);
}

// The grant of a burst requested now: at once when the path is free and no other process can
// make a request at this instant (what the arbiter would decide at the end of the instant),
// else through the arbiter.
sc_time PlbBus::acquire(Path& path, int master) {
    if (!path.in_flight && sc_core::sc_time_stamp() >= path.free_at && path.pending.empty() &&
        !sc_core::sc_pending_activity_at_current_time()) {
        path.in_flight = true;
        path.last_master = master;
        if (tracer_.vcd_on()) path.busy->write(true);
    } else {
        await_grant(path, master);
    }
    return sc_core::sc_time_stamp();
}

// Whether the master that holds the path may take it again for a burst starting at `at`
// (later than now) without going back to the kernel: no request is waiting, nothing can run
// before `at`, so no one else could have asked by then.
bool PlbBus::keeps_path(const Path& path, const sc_time& at) const {
    return path.pending.empty() && !sc_core::sc_pending_activity_at_current_time() &&
           at < sc_core::sc_time_stamp() + sc_core::sc_time_to_pending_activity();
}

void PlbBus::b_transport(int master, tlm::tlm_generic_payload& tx, sc_time& delay) {
    MasterStats& stats = master_stats_[master];
    const uint64_t address = tx.get_address();
    const uint64_t bytes = tx.get_data_length();
    ++tlm_transactions_;
    const Route* route = decode(address, bytes);
    if (route == nullptr) {
        // No slave claims the address: the bus answers after its address phase.
        tx.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
        delay += cycles(params_.clock, params_.arbitration_cycles + params_.address_cycles);
        ++decode_errors_;
        ++stats.errors;
        return;
    }
    // The bus is a synchronisation point: requests are arbitrated at their true time.
    if (delay > SC_ZERO_TIME) {
        sc_core::wait(delay);
        delay = SC_ZERO_TIME;
    }
    Path& path = tx.is_write() ? write_ : read_;
    unsigned char* data = tx.get_data_ptr();
    const uint64_t burst_bytes = uint64_t(master_burst_[size_t(master)]) * params_.width_bits / 8;
    const sc_time requested = sc_core::sc_time_stamp();
    sc_time first_grant, end = requested;  // `end`: the last granted burst's end
    for (uint64_t done = 0; done < std::max<uint64_t>(bytes, 1);) {
        const uint64_t n = std::min(burst_bytes, bytes - done);
        const sc_time asked = end;  // the next burst is requested as the one before ends
        sc_time granted;
        if (end > sc_core::sc_time_stamp() && keeps_path(path, end)) {
            granted = end;
        } else {
            if (end > sc_core::sc_time_stamp()) sc_core::wait(end - sc_core::sc_time_stamp());
            granted = acquire(path, master);
        }
        if (done == 0) first_grant = granted;
        // The slave serves this burst from its grant (annotated: it may lie ahead of now).
        const sc_time ahead = granted - sc_core::sc_time_stamp();
        sc_time slave_time = ahead;
        tx.set_address(address + done - route->base);
        tx.set_data_ptr(data + done);
        tx.set_data_length(unsigned(n));
        tx.set_streaming_width(unsigned(n));
        if (faults_ && faults_->bus_error(stats.name, stats.bursts + 1, granted.value()))
            tx.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);  // the slave never sees it
        else
            slaves[route->slave]->b_transport(tx, slave_time);
        const sc_time duration = burst_time(params_, n, slave_time - ahead);
        end = granted + duration;
        path.free_at = end;
        path.in_flight = false;
        ++stats.bursts;
        record_wait(stats, granted - asked);
        stats.busy += duration;
        ++path.stats.bursts;
        path.stats.busy += duration;
        path.series.busy(granted.value(), end.value());
        if (!tx.is_response_ok()) break;
        done += std::max<uint64_t>(n, 1);
    }
    tx.set_address(address);
    tx.set_data_ptr(data);
    tx.set_data_length(unsigned(bytes));
    tx.set_streaming_width(unsigned(bytes));
    if (!path.pending.empty() || tracer_.vcd_on()) path.arbitrate.notify(end - sc_core::sc_time_stamp());
    delay = end - sc_core::sc_time_stamp();

    (tx.is_write() ? stats.bytes_written : stats.bytes_read) += bytes;
    if (tx.get_response_status() != tlm::TLM_OK_RESPONSE) ++stats.errors;
    path.stats.bytes += bytes;
    if (tracer_.perfetto_on()) trace_transaction(master, tx.is_write(), address, bytes, requested, first_grant, end);
}

// The transaction on its master's track (its wait for the bus first) and on the data path's;
// its figures are arguments, so that slices of one kind aggregate.
void PlbBus::trace_transaction(int master, bool write, uint64_t address, uint64_t bytes, const sc_time& requested,
                               const sc_time& granted, const sc_time& end) {
    const int track = write ? master_tracks_[master].second : master_tracks_[master].first;
    const std::string& who = master_stats_[master].name;
    TraceArgs args;
    args.text("master", who).number("bytes", double(bytes)).address("address", address);
    if (granted > requested) tracer_.slice(track, "wait for the bus", requested, granted, args);
    const char* name = write ? "write" : "read";
    tracer_.slice(track, name, granted, end, args);
    tracer_.slice((write ? write_ : read_).track, fmt::format(FMT_COMPILE("{} {}"), who, name), granted, end, args);
}

bool PlbBus::get_direct_mem_ptr(int, tlm::tlm_generic_payload& tx, tlm::tlm_dmi& dmi) {
    const uint64_t address = tx.get_address();
    const Route* route = decode(address, 1);
    if (route == nullptr) return false;
    tx.set_address(address - route->base);
    const bool granted = slaves[route->slave]->get_direct_mem_ptr(tx, dmi);
    tx.set_address(address);
    if (!granted) return false;
    // Back to bus addresses, clipped to the region, with the bus's own per-access cost.
    dmi.set_start_address(dmi.get_start_address() + route->base);
    dmi.set_end_address(std::min<uint64_t>(dmi.get_end_address() + route->base, route->base + route->size - 1));
    const sc_time overhead = cycles(params_.clock, params_.arbitration_cycles + params_.address_cycles);
    dmi.set_read_latency(dmi.get_read_latency() + overhead);
    dmi.set_write_latency(dmi.get_write_latency() + overhead);
    return true;
}

unsigned PlbBus::transport_dbg(int, tlm::tlm_generic_payload& tx) {
    const uint64_t address = tx.get_address();
    const Route* route = decode(address, tx.get_data_length());
    if (route == nullptr) return 0;
    tx.set_address(address - route->base);
    const unsigned n = slaves[route->slave]->transport_dbg(tx);
    tx.set_address(address);
    return n;
}

void PlbBus::invalidate_direct_mem_ptr(int slave, sc_dt::uint64 start, sc_dt::uint64 end) {
    for (const Route& r : routes_) {
        if (r.slave != static_cast<unsigned>(slave) || start >= r.size) continue;
        const uint64_t last = std::min<uint64_t>(end, r.size - 1);
        for (unsigned m = 0; m < masters.size(); ++m)
            masters[m]->invalidate_direct_mem_ptr(r.base + start, r.base + last);
    }
}

void PlbBus::register_statistics(const Statistics::Scope& s) const {
    s.value("clock_hz", params_.clock.hz, "Hz", "bus clock");
    s.value("width_bits", params_.width_bits, "bit", "data width");
    for (const auto& [name, path] : {std::pair{"read", &read_}, std::pair{"write", &write_}}) {
        const Statistics::Scope d = s / name;
        d.count(
            "bursts", [path = path] { return path->stats.bursts; }, "bursts", "bursts on this data path");
        d.bytes(
            "bytes", [path = path] { return path->stats.bytes; }, "bytes on this data path");
        d.time(
            "busy_s", [path = path] { return path->stats.busy; }, "the data path carrying a burst");
        d.share(
            "utilisation", [path = path] { return path->stats.busy; }, "busy over the run");
        d.series("busy_series", path->series, "share", "busy share per time bin");
    }
    s.count(
        "decode_errors", [this] { return decode_errors_; }, "accesses", "addresses no slave answers");
    for (size_t i = 0; i < master_stats_.size(); ++i) {
        const Statistics::Scope m = s / "masters" / master_stats_[i].name;
        const MasterStats& st = master_stats_[i];
        m.count(
            "bursts", [&st] { return st.bursts; }, "bursts", "bursts granted");
        m.bytes(
            "bytes_read", [&st] { return st.bytes_read; }, "bytes read");
        m.bytes(
            "bytes_written", [&st] { return st.bytes_written; }, "bytes written");
        m.count(
            "errors", [&st] { return st.errors; }, "bursts", "error responses");
        m.time(
            "busy_s", [&st] { return st.busy; }, "from grant to the end of its bursts");
        m.time(
            "wait_s", [&st] { return st.wait; }, "from request to grant, summed");
        m.max_time(
            "max_wait_s", [&st] { return st.max_wait; }, "the longest wait for a grant");
        m.histogram(
            "bursts_by_wait_cycles",
            [&st] {
                std::vector<std::pair<std::string, uint64_t>> bins;
                for (size_t b = 0; b < st.wait_histogram.size(); ++b)
                    bins.emplace_back(wait_bin_name(b), st.wait_histogram[b]);
                return bins;
            },
            "bursts", "bursts by their wait in bus cycles");
    }
}

}  // namespace surfvp
