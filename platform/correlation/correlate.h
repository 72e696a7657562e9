#pragma once
// `surfvp correlate [SCENARIO]`: what the paper's lost Figure 3 must have said. The unknowns
// the paper's figures depend on most are varied over their bands, and each combination is kept
// or dropped by whether the VP then reproduces the paper's figures within their precision
// (docs/correlation.md):
// - the MasterController's schedule (bus word x line FIFO organisation x read buses): its basic
//   script against note 4's optimal state (about 11 %), from the generated sequence alone;
// - for each schedule that reproduces it, the frame rate at 1024x768 (about 10 frames/s) over
//   the FHG clock, the CPU clock, the APU FPU's clock ratio and the keypoints per frame (around
//   100), by re-simulation on the sweep's engine (2-frame runs, as the verdict's).
// Writes correlate.md, correlate.json and correlate.svg (frames/s against the FHG clock, the
// paper's range shaded) and says whether the scenario's own values lie inside the region.
#include <string>
#include <vector>

namespace surfvp {

struct CorrelateOptions {
    std::string scenario = "budget_1024x768";
    std::vector<std::string> sets;
    std::string out;    // default: traces/correlate_<scenario name>
    unsigned jobs = 0;  // 0: one per core
    bool quiet = false;
};

// 0 written; 2 bad input; 3 internal error; 4 a file could not be written.
int correlate_command(const CorrelateOptions& options);

}  // namespace surfvp
