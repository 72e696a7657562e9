#pragma once
// `surfvp run` and `surfvp validate`: load a scenario, elaborate the SoC, simulate until the
// software finishes, write the traces and reports. Exit codes are documented in README.md.
#include <string>
#include <vector>

namespace surfvp {

enum ExitCode { kExitOk = 0, kExitFailed = 1, kExitBadInput = 2, kExitInternal = 3 };

struct RunOptions {
    std::string scenario;
    std::vector<std::string> sets;
    std::string out;            // default: traces/<scenario name>
    std::string trace = "all";  // none | vcd | perfetto | all
    bool quiet = false;
    bool direct = false;  // no SystemC: the driver and software on the untimed DirectChip
};

// Both throw ConfigError for bad input; the caller turns it into kExitBadInput.
int run_scenario(const RunOptions& options);
int validate_scenario(const RunOptions& options);

}  // namespace surfvp
