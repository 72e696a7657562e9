#pragma once
// `surfvp run` and `surfvp validate`: load a scenario, check it, and run it into its output
// folder (all or nothing), with the verdict's re-simulations and a comparison when asked.
#include <string>
#include <vector>

namespace surfvp {

struct RunOptions {
    std::string scenario;
    std::vector<std::string> sets;
    std::string out;            // default: traces/<scenario name>
    std::string trace = "all";  // none | vcd | perfetto | all
    bool quiet = false;
    bool direct = false;     // no SystemC: the driver and software on the untimed DirectChip
    bool quick = false;      // without the verdict's re-simulations (verdict.break_even, band, software off)
    std::string compare_to;  // a run folder or SWEEP_DIR@N: compare.md and compare.json against it
};

// Both throw ConfigError for bad input; the caller turns it into kExitBadInput. Both print the
// scenario's stated warnings (parameters given that have no effect) on stderr.
int run_scenario(const RunOptions& options);
int validate_scenario(const RunOptions& options);

}  // namespace surfvp
