#pragma once
// `surfvp run` and `surfvp validate`: load a scenario, elaborate the SoC, simulate until the
// software finishes, write the traces and reports. Exit codes are documented in README.md.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "platform/scenario/config.h"

namespace surfvp {

enum ExitCode { kExitOk = 0, kExitFailed = 1, kExitBadInput = 2, kExitInternal = 3, kExitEnvironment = 4,
               kExitOutOfMemory = 5 };

struct RunOptions {
    std::string scenario;
    std::vector<std::string> sets;
    std::string out;            // default: traces/<scenario name>
    std::string trace = "all";  // none | vcd | perfetto | all
    bool quiet = false;
    bool direct = false;  // no SystemC: the driver and software on the untimed DirectChip
    std::string compare_to;  // a run folder or SWEEP_DIR@N: compare.md and compare.json against it
};

// Both throw ConfigError for bad input; the caller turns it into kExitBadInput. Both print the
// scenario's stated warnings (parameters given that have no effect) on stderr.
int run_scenario(const RunOptions& options);
int validate_scenario(const RunOptions& options);

// Everything about a loaded scenario that needs no simulation and no SystemC: the parameters'
// consistency, the files it names, the workload's layout. run and validate call it before
// anything is built or written; throws ConfigError at the first problem.
void check_scenario(const Config& config);

// One simulation of `config` on the VP and its report (not yet written), with the traces
// (`trace`: none, vcd, perfetto, all) and the workload's files written into `out` (nothing
// when `out` is empty). Throws ConfigError for bad input.
nlohmann::ordered_json simulate_scenario(const Config& config, const std::string& out, const std::string& trace, bool quiet);

// One run of `config` on the untimed DirectChip (no SystemC) into `dir`: report.json,
// config.yaml and the workload's files (its keypoints byte for byte the VP's); returns the
// run's exit code.
int run_direct(const Config& config, const std::filesystem::path& dir);

// Writes config.yaml, report.md, report.html, frames.csv and report.json of a run into `out`
// and returns the run's exit code.
int write_run(const Config& config, const std::string& out, const nlohmann::ordered_json& report);

}  // namespace surfvp
