// MciLink's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "mci_link.h"

namespace surfvp {

const ParamTable<MciLink::Params>& MciLink::parameter_table() {
    using P = Params;
    static const ParamTable<P> table(
        {field<P>({"mci.clock",
                   ParamKind::frequency,
                   "200 MHz",
                   1 * unit::MHz,
                   1000 * unit::MHz,
                   {},
                   "Clock of the PPC440's memory controller interface (CPMMCCLK)",
                   "[A] the MPMC's clock, which the PPC440MC port runs at (memory.clock)",
                   {"100 MHz", "266 MHz", "the MCI at the PLB clock, or with a DDR2-533 MPMC"}},
                  &P::clock),
         field<P>({"mci.width",
                   ParamKind::bits,
                   "128 bit",
                   32,
                   128,
                   {},
                   "Data width of the memory controller interface",
                   "[A] the PPC440 crossbar's 128-bit interfaces (docs/sources.md#mci)",
                   {"64 bit", "128 bit", "a narrower memory interface than the crossbar's"}},
                  &P::width_bits),
         field<P>({"mci.latency",
                   ParamKind::cycles,
                   "4 cycles",
                   0,
                   1000,
                   {},
                   "Cycles of mci.clock the crossbar and the MCI add to an access before the DDR sees it",
                   "[A] a request through the crossbar and the interface's address phase, like a PLB burst's overhead",
                   {"2 cycles", "8 cycles", "crossbar and clock-crossing cycles are not retrieved"}},
                  &P::latency_cycles)});
    return table;
}

}  // namespace surfvp
