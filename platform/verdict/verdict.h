#pragma once
// The budget verdict with its doubt (DESIGN principle 7), found by re-simulating the scenario:
// - margin: frames/s against the budget, and each resource's slack (frame_limits.h);
// - break-even (`verdict.break_even`): the value of the limiting block's clock (and, for the
//   FHG, of its cycles per block) that just meets the budget, found by a search of
//   re-simulations and checked by one more run of the whole scenario at that value;
// - assumption band (`verdict.band`): every parameter with a band (parameters.h) at its low
//   and at its high, one at a time: the frames/s range, the assumptions that flip the verdict,
//   a tornado chart (tornado.svg);
// - software settings (`verdict.software`): the settings the CPU's time rests on (Haar mode,
//   upright, keypoints per frame), each value other than the scenario's: frames/s, CPU time.
// Re-simulations run `verdict.frames` frames (the pipeline is in steady state after the
// first), each in a child process forked from this one (SystemC elaborates once per process;
// the children inherit the frames, the threshold calibration and the FHG sequences this
// process has prepared), `verdict.jobs` at a time. Results do not depend on the jobs.
#include <string>

#include "platform/scenario/config.h"

namespace surfvp {

bool verdict_requested(const Config& config);

// Runs the scenario (its outputs into `out`, traces as `trace` asks) and the analyses its
// `verdict.*` parameters ask for; writes the reports with a "verdict" section; returns the
// run's exit code. Throws ConfigError for bad input.
int run_with_verdict(const Config& config, const std::string& out, const std::string& trace, bool quiet);

}  // namespace surfvp
