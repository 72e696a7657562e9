#pragma once
// `surfvp bench`: how fast the simulator runs a scenario, against the chip it models and the
// float reference SURF. SystemC simulates once per process, so each measurement is a child
// `surfvp run` (the verdict's re-simulations off), the fastest of three taken in rounds that
// interleave the modes compared (traces off, all, direct); the wall time per frame is the
// difference between the simulations of N and 2N frames (report.json wall_time_s), divided by N
// (a ratio of two modes' is the median of the rounds' own), and start-up is the run's own startup_s: from the process's start
// (the dynamic loader included) to the simulation's (loading, calibration, the sequence,
// elaboration). A SURF scenario is also run in direct mode the same way, and the VP's time
// per frame (traces off) over direct mode's is its speed-up. Printed as JSON with the
// targets beside the figures (docs/architecture.md, "Simulation speed").
#include <string>

namespace surfvp {

struct BenchOptions {
    std::string scenario = "budget_1024x768";
    unsigned frames = 10;
    bool scaling = false;  // also 640x480 and 1024x1024 frames, and 10x as many frames
    std::string self;      // this executable
};

int bench_command(const BenchOptions& options);

}  // namespace surfvp
