#pragma once
// `surfvp table2 SCENARIO`: the paper's Table II through the modelled chip. The scenario's
// frames go through the chip ("FPGA": the driver, cores and software of a run, in direct mode,
// whose keypoints are the VP's byte for byte) and through the float reference SURF beside it
// ("CPU": sw/surf at its defaults, 4 octaves), both at the scenario's keypoint budget under the
// same threshold rule; then distinguishability on every pair (i, i + gap) for the four rows
// (limited search Y/N x Laplacian Y/N), with F from RANSAC and, where the scenario has camera
// poses, from the ground truth; under a homography also repeatability and precision. Writes
// report.md and report.json next to the paper's own figures (a labelled reference, never a
// result); docs/table2.md is the user's description.
#include <string>
#include <vector>

namespace surfvp {

struct Table2Options {
    std::string scenario;
    std::vector<std::string> sets;
    std::string out;  // default: traces/<scenario name>
    bool quiet = false;
};

// Exit codes as `surfvp run`: 0 written, 1 the chip run failed a check (the tables are still
// written, and say so), 2 bad input, 3 internal error, 4 a file could not be written.
int table2_command(const Table2Options& options);

}  // namespace surfvp
