// Dma's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "dma.h"

namespace surfvp {

const ParamTable<Dma::Params>& Dma::parameter_table() {
    using P = Params;
    static const ParamTable<P> table({
        field<P>({"dma.burst", ParamKind::beats, "16 beats", 1, 16, {}, "Burst length of the test DMA on PLB2",
           "[A] the longest PLB burst",
           {"8 beats", "16 beats",
            "the test DMA's own bursts"}},
                 &P::burst_beats),
        field<P>({"dma.register_latency", ParamKind::cycles, "2 cycles", 0, 64, {},
           "Test DMA registers: PLB1 cycles from the address phase to the register's data",
           "[A] an XPS PLBv46 slave (IPIF) decodes the address and registers its data: a few cycles (DS561 "
           "timing not retrieved)",
           {"1 cycle", "4 cycles",
            "as intc.register_latency"}},
                 [](P& p) -> unsigned& { return p.registers.cycles; })
    });
    return table;
}

}  // namespace surfvp
