#pragma once
// What a run of the chip is, apart from any block: the software the CPU runs, the SoC's
// accelerator pairs and the CPU's path to memory, and the simulation's own settings (the
// stall guard, report.html's time bins, the FHG's second thread, DMA transaction size). The
// wiring (block_params.cpp, soc.cpp) and the run loop read them through RunSettings.
#include <string>

#include "models/common/parameter.h"

namespace surfvp {

struct RunSettings {
    std::string workload;             // run.workload: "smoke" or "surf"
    Duration max_time;                // run.max_time: the stall guard
    Duration series_bin;              // run.series_bin: report.html's time bins
    bool parallel = true;             // run.parallel: FHG rows on a second thread
    bool dma_per_burst = false;       // run.dma_granularity: one TLM transaction per burst, not per line
    bool cpu_memory_on_plb1 = false;  // cpu.memory_path: plb1 rather than the MCI
    unsigned accelerators = 1;        // soc.accelerators: IIG + FHG pairs

    static const ParamTable<RunSettings>& parameter_table();
};
RunSettings run_settings(const ParamValues& values);

}  // namespace surfvp
