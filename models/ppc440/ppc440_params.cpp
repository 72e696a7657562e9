// Ppc440's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "ppc440.h"

namespace surfvp {

const ParamTable<Ppc440::Params>& Ppc440::parameter_table() {
    using P = Params;
    static const ParamTable<P> table(
        {field<P>({"cpu.clock",
                   ParamKind::frequency,
                   "400 MHz",
                   1 * unit::MHz,
                   550 * unit::MHz,
                   {},
                   "PowerPC 440 core clock",
                   "[S] ML507 reference design (Linux virtex440-ml507.dts, QEMU virtex_ml507): 400 MHz; 550 MHz is the "
                   "device maximum",
                   {"300 MHz", "550 MHz",
                    "the seed's CPU clock is not given: the ML507 design runs 400, FX designs run 250-400, the device "
                    "allows 550"}},
                  &P::clock),
         field<P>({"cpu.quantum",
                   ParamKind::duration,
                   "1 us",
                   1,
                   1000 * unit::us,
                   {},
                   "Temporal-decoupling quantum: how far the CPU runs ahead of the kernel between synchronisations",
                   "[-] simulation setting (no figure depends on it): 100 PLB cycles, coarse enough to be fast"},
                  &P::quantum),
         field<P>({"cpu.cache_line",
                   ParamKind::bytes,
                   "32 B",
                   4,
                   256,
                   {},
                   "L1 cache line: the CPU's memory traffic goes in lines",
                   "[S] ML507 DTS: 32-byte L1 lines"},
                  &P::line_bytes),
         field<P>({"cpu.outstanding_fills",
                   ParamKind::count,
                   "3",
                   1,
                   16,
                   {},
                   "L1 line fills the CPU has in flight at once: a miss beyond them waits for the oldest",
                   "[S] PPC440x5 CPU core user's manual: up to three outstanding line fills (and four load misses)",
                   {"1", "3", "a blocking cache, one fill at a time"}},
                  &P::outstanding_fills),
         field<P>({"cpu.critical_word_first",
                   ParamKind::choice,
                   "on",
                   0,
                   0,
                   {"on", "off"},
                   "A fill hands the CPU the word it missed on first (on), or only the whole line (off)",
                   "[S] PPC440x5 CPU core user's manual: line fills deliver the critical word first",
                   {"off", "on", "the CPU waits for the whole line"}},
                  &P::critical_word_first)});
    return table;
}

}  // namespace surfvp
