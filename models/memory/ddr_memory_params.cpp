// DdrMemory's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "ddr_memory.h"

namespace surfvp {

const ParamTable<DdrMemory::Params>& DdrMemory::parameter_table() {
    using P = Params;
    static const ParamTable<P> table({
        field<P>({"memory.size", ParamKind::bytes, "256 MiB", 1 * unit::MiB, 256 * unit::MiB, {}, "Installed DDR", "[S] ML507: 256 MB DDR2"},
                 &P::size),
        field<P>({"memory.clock", ParamKind::frequency, "200 MHz", 50 * unit::MHz, 800 * unit::MHz, {}, "DDR clock",
           "[A] DDR2 at ~200 MHz on the ML507 class of boards",
           {"133 MHz", "266 MHz",
            "DDR2-266 to DDR2-533 on the ML507 class of boards"}},
                 &P::clock),
        field<P>({"memory.width", ParamKind::bits, "64 bit", 8, 256, {}, "DDR data width", "[A] 64-bit DDR2 DIMM",
           {"32 bit", "64 bit",
            "a 32-bit DDR2 component instead of the 64-bit DIMM"}},
                 &P::width_bits),
        field<P>({"memory.transfers_per_clock", ParamKind::count, "2", 1, 2, {}, "Data transfers per clock (2 for DDR)",
           "[S] DDR transfers on both clock edges"},
                 &P::transfers_per_clock),
        field<P>({"memory.efficiency", ParamKind::real, "0.8", 0.01, 1, {},
           "Fraction of the peak bandwidth that sustained traffic gets",
           "[A] ~80 % burst efficiency (docs/sources.md#ddr)",
           {"0.6", "0.9",
            "row misses and refresh: 60-90 % of the peak"}},
                 &P::efficiency),
        field<P>({"memory.latency", ParamKind::cycles, "25 cycles", 0, 1000, {},
           "Read latency at the DDR clock, before the first data",
           "[A] ~20-30 MPMC cycles read latency, no DS643 table retrieved (docs/sources.md#ddr)",
           {"20 cycles", "30 cycles",
            "~20-30 MPMC cycles (docs/sources.md#ddr)"}},
                 &P::latency_cycles),
        field<P>({"memory.write_latency", ParamKind::cycles, "0 cycles", 0, 1000, {},
           "Latency a write's master sees at the DDR clock (it still waits for the DRAM and its transfer)",
           "[A] the MPMC's ports take writes into a write FIFO (DS643: ports with FIFOs): posted",
           {"0 cycles", "25 cycles",
            "posted into a write FIFO, or as slow as a read"}},
                 &P::write_latency_cycles)
    });
    return table;
}

}  // namespace surfvp
