#pragma once
// The run loop: elaborate the SoC for a loaded scenario, simulate until the software
// finishes, and write the traces and reports; or run the same software on the untimed
// DirectChip. The commands (cli/run_command.h, the verdict, sweeps) are built on it. Exit codes
// are documented in README.md.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/common/tracer.h"
#include "platform/scenario/config.h"

namespace surfvp {

enum ExitCode {
    kExitOk = 0,
    kExitFailed = 1,
    kExitBadInput = 2,
    kExitInternal = 3,
    kExitEnvironment = 4,
    kExitOutOfMemory = 5,
    kExitBroken = 6  // the run broke: the software stalled or failed, a frame was lost, a fault not recovered
};

// A finished run's exit code from its report: kExitOk when it passed, kExitBroken when it
// broke ("broken"), kExitFailed when it only missed a goal (the budget, a keypoint target).
int exit_code_of(const nlohmann::ordered_json& report);

// Everything about a loaded scenario that needs no simulation and no SystemC: the parameters'
// consistency, the files it names, the workload's layout. run and validate call it before
// anything is built or written; throws ConfigError at the first problem.
void check_scenario(const Config& config);

// The trace files a --trace mode asks for (none, vcd, perfetto, all) under `dir`; throws
// ConfigError for another mode.
Tracer::Options trace_options(const std::string& mode, const std::string& dir);

// One simulation of `config` on the VP and its report (not yet written), with the traces
// (`trace`: none, vcd, perfetto, all) and the workload's files written into `out` (nothing
// when `out` is empty). Throws ConfigError for bad input.
nlohmann::ordered_json simulate_scenario(const Config& config, const std::string& out, const std::string& trace,
                                         bool quiet);

// One run of `config` on the untimed DirectChip (no SystemC) into `dir`: report.json,
// config.yaml and the workload's files (its keypoints byte for byte the VP's); returns the
// run's exit code.
int run_direct(const Config& config, const std::filesystem::path& dir);

// Writes config.yaml, report.md, report.html, frames.csv and report.json of a run into `out`
// and returns the run's exit code.
int write_run(const Config& config, const std::string& out, const nlohmann::ordered_json& report);

}  // namespace surfvp
