#pragma once
// DDR memory behind a multi-port controller (the EDK MPMC, DS643; docs/sources.md#ddr).
// Each path to it binds its own port (PLB2 for the DMA masters, the PPC440's memory
// controller interface or PLB1 for the CPU). The DRAM itself is one shared resource: an
// access takes the DRAM for its transfer at the controller's bandwidth, at the earliest
// free interval from its request (BusyTimeline), and is done after the access latency:
//   bandwidth = width x clock x transfers_per_clock x efficiency
//   start     = the first gap >= request that fits bytes / bandwidth
//   done      = start + latency + bytes / bandwidth
// The latency of one access overlaps the transfers of others (the controller pipelines
// commands), so only transfers occupy the DRAM. A read waits out `latency_cycles`; a write is
// posted into the port's write FIFO and sees `write_latency_cycles` (it still waits for the
// DRAM and takes its transfer time). DMI gives a pointer to the storage (one array, byte
// order as in byte_order.h) for reading in place; its users account their time separately.
#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <tlm>
#include <tlm_utils/multi_passthrough_target_socket.h>
#include <vector>

#include "busy_timeline.h"
#include "models/common/statistics.h"
#include "models/common/parameter.h"
#include "models/common/zeroed_memory.h"
#include "models/common/units.h"

namespace surfvp {

class DdrMemory : public sc_core::sc_module {
public:
    struct Params {
        Bytes size{256ull << 20};
        Frequency clock{200e6};
        unsigned width_bits = 64;
        unsigned transfers_per_clock = 2;    // DDR: two transfers per clock
        double efficiency = 0.8;             // fraction of the peak that sustained traffic gets
        unsigned latency_cycles = 25;        // a read's, before the first data
        unsigned write_latency_cycles = 0;   // a write's, as its master sees it (posted)
        Duration series_bin{1'000'000'000};  // report.html's time bins (the wiring's run.series_bin)
        bool populate_ahead = true;          // written pages faulted in on a second thread (the wiring's run.parallel)
    };
    // Its scenario parameters with the Params field each sets (ddr_memory_params.cpp).
    static const ParamTable<Params>& parameter_table();

    struct PortStats {
        std::string name;
        uint64_t reads = 0, writes = 0;
        uint64_t bytes_read = 0, bytes_written = 0;
        sc_core::sc_time wait;  // time spent waiting for the DRAM behind other accesses
    };

    tlm_utils::multi_passthrough_target_socket<DdrMemory> ports;

    DdrMemory(const sc_core::sc_module_name& name, const Params& params);
    ~DdrMemory() override;  // the storage given back in the background

    // Names the next port binding (for the report); call in binding order.
    void name_port(const std::string& name);

    // Uncontended time of one read of `bytes`, the formula above.
    sc_core::sc_time access_time(uint64_t bytes) const { return read_time(params_, bytes); }
    static sc_core::sc_time read_time(const Params& params, uint64_t bytes);
    static double bytes_per_second(const Params& params);
    sc_core::sc_time latency() const;
    double bytes_per_second() const;

    // Untimed backdoor for loaders and tests: the storage of [address, address + bytes).
    // Throws std::out_of_range outside the installed size.
    uint8_t* backdoor(uint64_t address, uint64_t bytes);

    const std::vector<PortStats>& port_stats() const { return port_stats_; }
    sc_core::sc_time busy() const { return busy_; }
    const Params& params() const { return params_; }

    // Its statistics, registered at elaboration (after every connection) under `scope`.
    void register_statistics(const Statistics::Scope& scope) const;

private:
    void b_transport(int port, tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
    bool get_direct_mem_ptr(int port, tlm::tlm_generic_payload& tx, tlm::tlm_dmi& dmi);
    unsigned transport_dbg(int port, tlm::tlm_generic_payload& tx);
    bool check(tlm::tlm_generic_payload& tx) const;
    PortStats& stats(int port);

    Params params_;
    // Per access, from params_ once (the same formulas, so the same values).
    double bytes_per_second_;
    sc_core::sc_time read_latency_, write_latency_;
    ZeroedMemory storage_;
    std::unique_ptr<PopulateAhead> populate_;  // with Params::populate_ahead; goes before storage_
    std::vector<PortStats> port_stats_;
    BusyTimeline dram_;
    sc_core::sc_time busy_;
    TimeSeries series_;  // busy share per time bin
};

}  // namespace surfvp
