#pragma once
// PLB v4.6 bus (Xilinx DS531/DS561; docs/sources.md#plb): address decode from the address map,
// arbitration among several masters (round-robin or fixed priority), a data width and a
// clock, fixed bursts of up to `max_burst_beats`, separate read and write data paths.
//
// The unit of the bus is the burst. A transaction of any length is carried as the bursts it
// stands for (beats = ceil(B / (width/8)), up to the master's burst length each), and every burst is
// arbitrated on its own: another master's request is granted at the next burst boundary,
// exactly as if the first master had issued one transaction per burst. One burst of b beats
// granted at time g:
//   end = g + (arbitration + address) cycles + max(b cycles, slave time)
// The slave's time (its wait, latency and transfer, which the memory model returns) overlaps
// the data beats: the data stream runs at the slower of the two.
//
// Contention is exact at burst granularity: a master's request waits until its local time,
// joins the path's queue, and an arbiter grants the path when it is free, picking among the
// requests present by the policy. For speed, a master keeps the path for its next burst
// without a kernel event when nothing else can happen before that burst starts (no other
// request, no process runnable now, no event due earlier): the result is the same. Wait time
// and busy time are recorded per master and per burst. Slaves must answer without wait().
#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/multi_passthrough_initiator_socket.h>
#include <tlm_utils/multi_passthrough_target_socket.h>
#include <vector>

#include "models/common/fault_plan.h"
#include "models/common/statistics.h"
#include "models/common/parameter.h"
#include "models/common/tracer.h"
#include "models/common/units.h"

namespace surfvp {

class PlbBus : public sc_core::sc_module {
public:
    enum class Arbitration { round_robin, fixed_priority };

    struct Params {
        Frequency clock{100e6};
        unsigned width_bits = 128;
        unsigned max_burst_beats = 16;
        unsigned arbitration_cycles = 3;
        unsigned address_cycles = 1;
        Arbitration arbitration = Arbitration::round_robin;
        Duration series_bin{1'000'000'000};  // report.html's time bins (the wiring's run.series_bin)
    };
    // The scenario parameters of the bus named `bus` ("plb1"), with the Params field each sets
    // (plb_params.cpp); the two PLBs differ only in their width's default and its source.
    static ParamTable<Params> parameter_table(const std::string& bus, const std::string& width,
                                              const std::string& width_source, const std::string& role);

    struct MasterStats {
        std::string name;
        uint64_t bursts = 0;
        uint64_t bytes_read = 0;
        uint64_t bytes_written = 0;
        uint64_t errors = 0;
        sc_core::sc_time wait;  // from request to grant, summed
        sc_core::sc_time max_wait;
        // Bursts by their wait in bus cycles: 0, 1, 2-3, 4-7, ... 64 and more (wait_bin_name).
        std::array<uint64_t, 8> wait_histogram{};
        sc_core::sc_time busy;  // from grant to end, summed
    };
    static std::string wait_bin_name(size_t bin);

    struct PathStats {
        uint64_t bursts = 0;
        uint64_t bytes = 0;
        sc_core::sc_time busy;
    };

    tlm_utils::multi_passthrough_target_socket<PlbBus> masters;  // bind with connect_master()
    tlm_utils::multi_passthrough_initiator_socket<PlbBus> slaves;

    PlbBus(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer);

    // Masters are numbered in the order they connect; with fixed priority, 0 is highest. A
    // master's bursts are at most `burst_beats` long (its DMA's own burst length; 0: the
    // bus's max_burst_beats), whatever the length of its transactions.
    void connect_master(tlm::tlm_base_initiator_socket<>& socket, const std::string& name, unsigned burst_beats = 0);
    // The region [base, base+size) goes to `slave` (the index of its slaves binding); the
    // slave sees addresses relative to base.
    void map(uint64_t base, uint64_t size, unsigned slave, const std::string& name);

    // The documented formula for an uncontended transaction with a zero-time slave.
    sc_core::sc_time transaction_time(uint64_t bytes) const;
    // One burst of `bytes` whose slave takes `slave_time`: overhead + max(beats, slave).
    static sc_core::sc_time burst_time(const Params& params, uint64_t bytes, const sc_core::sc_time& slave_time);

    const Params& params() const { return params_; }
    const std::vector<MasterStats>& master_stats() const { return master_stats_; }
    // Faults to inject (bus_error: a master's Nth burst answered with an error); none by default.
    void set_faults(FaultPlan* faults) { faults_ = faults; }
    const PathStats& read_stats() const { return read_.stats; }
    const PathStats& write_stats() const { return write_.stats; }
    uint64_t decode_errors() const { return decode_errors_; }
    uint64_t tlm_transactions() const {
        return tlm_transactions_;
    }  // a simulation figure: depends on how masters batch

    // Its statistics, registered at elaboration (after every connection) under `scope`.
    void register_statistics(const Statistics::Scope& scope) const;

private:
    struct Route {
        uint64_t base;
        uint64_t size;
        unsigned slave;
        std::string name;
    };
    struct Request {
        int master;
        sc_core::sc_time requested;
    };
    struct Path {
        explicit Path(const char* path_name) : name(path_name) {}
        const char* name;
        std::vector<Request> pending;
        sc_core::sc_time free_at;
        bool in_flight = false;  // granted, end not yet known
        bool deciding = false;   // waiting for the end of the instant (every same-time request in)
        int last_master = -1;
        sc_core::sc_event arbitrate;
        std::deque<sc_core::sc_event> granted;  // one per master
        std::unique_ptr<sc_core::sc_signal<bool, sc_core::SC_UNCHECKED_WRITERS>>
            busy;  // written by the arbiter and by a master granted at once
        PathStats stats;
        TimeSeries series;  // busy share per time bin
        int track = -1;
    };

    void b_transport(int master, tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
    bool get_direct_mem_ptr(int master, tlm::tlm_generic_payload& tx, tlm::tlm_dmi& dmi);
    unsigned transport_dbg(int master, tlm::tlm_generic_payload& tx);
    void invalidate_direct_mem_ptr(int slave, sc_dt::uint64 start, sc_dt::uint64 end);

    void arbitrate(Path* path);
    void decide(Path* path);
    int pick(const Path& path) const;
    void await_grant(Path& path, int master);
    void record_wait(MasterStats& stats, const sc_core::sc_time& wait) const;
    sc_core::sc_time acquire(Path& path, int master);
    bool keeps_path(const Path& path, const sc_core::sc_time& at) const;
    const Route* decode(uint64_t address, uint64_t length) const;
    void trace_transaction(int master, bool write, uint64_t address, uint64_t bytes, const sc_core::sc_time& requested,
                           const sc_core::sc_time& granted, const sc_core::sc_time& end);
    void start_of_simulation() override;

    Params params_;
    Tracer& tracer_;
    std::vector<Route> routes_;
    std::vector<MasterStats> master_stats_;
    std::vector<std::pair<int, int>> master_tracks_;  // each master's read and write tracks
    std::vector<unsigned> master_burst_;              // beats per burst, per master
    FaultPlan* faults_ = nullptr;
    Path read_{Path("read")};
    Path write_{Path("write")};
    uint64_t decode_errors_ = 0;
    uint64_t tlm_transactions_ = 0;
};

}  // namespace surfvp
