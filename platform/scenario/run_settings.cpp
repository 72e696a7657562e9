// RunSettings' scenario parameters, each bound to the field it sets.
#include "platform/scenario/run_settings.h"

#include <fmt/format.h>

#include "models/common/time_series.h"

namespace surfvp {

using unit::us, unit::s;

const ParamTable<RunSettings>& RunSettings::parameter_table() {
    using P = RunSettings;
    static const ParamTable<P> table(
        {field<P>({"run.workload",
                   ParamKind::choice,
                   "smoke",
                   0,
                   0,
                   {"smoke", "surf"},
                   "What the CPU runs: the bus smoke test, or libSSA2 and SURF on frames",
                   "[-] scenario choice"},
                  &P::workload),
         field<P>({"run.max_time",
                   ParamKind::duration,
                   "600 s",
                   1,
                   36000 * s,
                   {},
                   "Simulated time after which a run that has not finished is stopped as stalled",
                   "[-] tool setting: a guard against a livelocked run, far above any shipped scenario (castle, exact "
                   "Haar: 11 s)"},
                  &P::max_time),
         field<P>({"run.series_bin",
                   ParamKind::duration,
                   "1 ms",
                   1 * us,
                   1 * s,
                   {},
                   fmt::format(
                       "Width of the time bins of report.html's charts (bus utilisation and FIFO levels over time); a "
                       "run longer than {} bins merges them by twos, so a series never holds more",
                       TimeSeries::kMaxBins),
                   "[-] report setting: a 118 ms frame in about a hundred bins"},
                  &P::series_bin),
         field<P>({"run.parallel",
                   ParamKind::choice,
                   "on",
                   0,
                   0,
                   {"on", "off"},
                   "Compute each FHG block row's determinants and maxima on a second thread while the kernel simulates "
                   "the row's cycles; off: in the simulation's own thread. The results are the same either way",
                   "[-] simulation setting (no figure depends on it)"},
                  &P::parallel),
         choice<P, bool>(
             {"run.dma_granularity",
              ParamKind::choice,
              "line",
              0,
              0,
              {},
              "IP blocks' DMA: one TLM transaction per line or per burst; the bus arbitrates every burst either "
              "way, so the figures are the same",
              "[-] simulation setting (no figure depends on it)"},
             &P::dma_per_burst, {{"line", false}, {"burst", true}}),
         choice<P, bool>(
             {"cpu.memory_path",
              ParamKind::choice,
              "mci",
              0,
              0,
              {},
              "How the CPU's line fills, write-backs and copies reach DDR: its crossbar and memory controller "
              "interface (the MPMC's PPC440MC port), or PLB1",
              "[A] the PPC440 block has a PPC440MC interface (docs/sources.md#mci); EDK designs for the ML507 wire "
              "the MPMC to it (recalled, not retrieved)"},
             &P::cpu_memory_on_plb1, {{"mci", false}, {"plb1", true}}),
         field<P>({"soc.accelerators",
                   ParamKind::count,
                   "1",
                   1,
                   4,
                   {},
                   "SSA IIG + SSA FHG pairs on the chip",
                   "[S] paper §III-D: one pair; the library supports more"},
                  &P::accelerators)});
    return table;
}

RunSettings run_settings(const ParamValues& values) { return RunSettings::parameter_table().make(values); }

}  // namespace surfvp
