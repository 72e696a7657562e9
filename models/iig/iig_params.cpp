// Iig's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "iig.h"

namespace surfvp {

const ParamTable<Iig::Params>& Iig::parameter_table() {
    using P = Params;
    static const ParamTable<P> table({
        field<P>({"iig.clock", ParamKind::frequency, "100 MHz", 1 * unit::MHz, 500 * unit::MHz, {}, "SSA IIG clock",
           "[A] the PLB clock of the ML507 design; Fig. 3's clocks are lost",
           {"50 MHz", "125 MHz",
            "Fig. 3's clocks are lost: half the PLB clock to the FHG's upper guess"}},
                 &P::clock),
        field<P>({"iig.pixels_per_clock", ParamKind::count, "1", 1, 16, {}, "Pixels the integral core adds per clock",
           "[A] one adder chain: 7.9 ms for 1024x768 at 100 MHz (docs/sources.md#iig)",
           {"1", "2",
            "one adder chain, or two"}},
                 &P::pixels_per_clock),
        field<P>({"iig.sum_bits", ParamKind::bits, "28 bit", 16, 32, {},
           "Significant bits of an integral value (in a 32-bit word); a larger sum is an error",
           "[D] 255 x 1024 x 1024 < 2^28: enough for the 1024x1024 limit"},
                 &P::sum_bits),
        field<P>({"iig.burst", ParamKind::beats, "16 beats", 1, 16, {}, "IIG DMA burst length on PLB2", "[A] the longest PLB burst",
           {"8 beats", "16 beats",
            "a DMA with shorter bursts"}},
                 &P::burst_beats),
        field<P>({"iig.line_buffers", ParamKind::count, "2", 1, 64, {},
           "Lines queued between the IIG's fetch, compute, write and send units",
           "[A] double buffering: one line in work, one waiting",
           {"1", "4",
            "single buffering, or deeper queues"}},
                 &P::line_buffers),
        register_latency<P>("iig", "SSA IIG registers", "as intc.register_latency"),
        field<P>({"iig.max_width", ParamKind::count, "1024", 1, 4096, {}, "Widest image the IIG accepts",
           "[S] paper §III: image size limit 1024 x 1024"},
                 &P::max_width),
        field<P>({"iig.max_height", ParamKind::count, "1024", 1, 4096, {}, "Tallest image the IIG accepts",
           "[S] paper §III: image size limit 1024 x 1024"},
                 &P::max_height),
        field<P>({"pixelbus.width", ParamKind::bits, "32 bit", 8, 128, {}, "PixelBus width: integral values per IIG cycle x 32",
           "[A] one 32-bit integral value per cycle (docs/sources.md#pixelbus)",
           {"32 bit", "64 bit",
            "one value a cycle is the least that keeps up; two would be wider"}},
                 &P::pixelbus_width_bits)
    });
    return table;
}

}  // namespace surfvp
