#pragma once
// The PPC440's own path to DDR on the Virtex-5 FX: its crossbar and memory controller
// interface (MCI), wired to the MPMC's PPC440MC port (the PPC440 block's PPC440MC
// interface). One master, the CPU's caches, so no arbitration: a read asked for a later time
// (the CPU hands over a step's line fills at the times the step needs them) waits in the
// kernel until it reaches the DRAM, so the DDR serves the CPU and the DMA in request order,
// and returns annotated with its end; a write is posted (annotated, never waits). An access of B bytes requested
// at r starts when the link is free, s = max(r, free), and ends at
//   s + latency cycles + max(ceil(B / (width/8)) cycles, DDR time)
// where the DDR time is the memory's own (its wait for the DRAM, latency and transfer): the
// DDR sees the CPU's traffic on its own port and it contends there with PLB2's DMA. The link
// is taken for its own cycles only (address phase and data beats): the DRAM's latency of one
// access overlaps the next request, so the CPU's outstanding fills pipeline through it.
#include <cstdint>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include "models/common/statistics.h"
#include "models/common/parameter.h"
#include "models/common/units.h"

namespace surfvp {

class MciLink : public sc_core::sc_module {
public:
    struct Params {
        Frequency clock{200e6};
        unsigned width_bits = 128;
        unsigned latency_cycles = 4;  // crossbar request and MCI address phase
    };
    // Its scenario parameters with the Params field each sets (mci_link_params.cpp).
    static const ParamTable<Params>& parameter_table();

    struct Stats {
        uint64_t reads = 0, writes = 0, bytes_read = 0, bytes_written = 0;
        sc_core::sc_time wait;  // requests waiting for the link behind earlier ones
        sc_core::sc_time busy;  // the link's own cycles: address phases and data beats
    };

    tlm_utils::simple_target_socket<MciLink> cpu;
    tlm_utils::simple_initiator_socket<MciLink> memory;

    MciLink(const sc_core::sc_module_name& name, const Params& params);

    // An uncontended access of `bytes` whose DDR time is `memory_time`.
    static sc_core::sc_time access_time(const Params& params, uint64_t bytes, const sc_core::sc_time& memory_time);
    // What an access of `bytes` takes the link for: its address phase and data beats.
    static sc_core::sc_time own_time(const Params& params, uint64_t bytes);

    const Stats& stats() const { return stats_; }
    const Params& params() const { return params_; }

    // Its statistics, registered at elaboration (after every connection) under `scope`.
    void register_statistics(const Statistics::Scope& scope) const;

private:
    void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
    bool get_direct_mem_ptr(tlm::tlm_generic_payload& tx, tlm::tlm_dmi& dmi);
    unsigned transport_dbg(tlm::tlm_generic_payload& tx);

    Params params_;
    sc_core::sc_time free_at_;
    Stats stats_;
};

}  // namespace surfvp
