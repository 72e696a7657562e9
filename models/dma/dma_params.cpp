// Dma's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "dma.h"

namespace surfvp {

const ParamTable<Dma::Params>& Dma::parameter_table() {
    using P = Params;
    static const ParamTable<P> table({field<P>({"dma.burst",
                                                ParamKind::beats,
                                                "16 beats",
                                                1,
                                                16,
                                                {},
                                                "Burst length of the test DMA on PLB2",
                                                "[A] the longest PLB burst",
                                                {"8 beats", "16 beats", "the test DMA's own bursts"}},
                                               &P::burst_beats),
                                      register_latency<P>("dma", "Test DMA registers", "as intc.register_latency")});
    return table;
}

}  // namespace surfvp
