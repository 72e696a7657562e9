#pragma once
// The budget verdict with its doubt (docs/architecture.md#principles, 7), found by re-simulating the scenario:
// - margin: frames/s against the budget, and each resource's slack (frame_limits.h);
// - the chain of limits (`verdict.break_even`, limit_chain.h): the limit's break-even on the
//   parameters of its cause, checked by a run of the whole scenario, then the limit relieved
//   there and the next one named with its headroom, up to three;
// - the doubt (`verdict.band`): the unknowns about the chip sampled jointly (doubt.h: the
//   frames/s percentiles, the probability of meeting the budget, each unknown's Sobol indices)
//   and each at its low and its high, one at a time (tornado.svg); the design choices and the
//   workload with a band, one at a time, apart (what a review can change);
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
