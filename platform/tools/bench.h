#pragma once
// `surfvp bench`: how fast the simulator runs a scenario, against the chip it models and the
// float reference SURF. SystemC simulates once per process, so each measurement is a child
// `surfvp run` of N frames (the verdict's re-simulations off), three rounds of them that
// interleave the modes compared (traces off, all, direct). The wall time per frame is a run's
// own: the slope of the times its frames were reported at (report.json frame_wall_s) over the
// last three quarters, the fastest round's; a ratio of two modes is the median of the rounds'
// own. Start-up is the run's own startup_s: from the process's start (the dynamic loader
// included) to the simulation's (loading, calibration, the sequence, elaboration). A SURF
// scenario is also run in direct mode the same way, and the VP's time per frame (traces off)
// over direct mode's is its speed-up, beside the same ratio of whole runs (start to exit, as a
// sweep's point waits for them). Printed as JSON with the targets beside the figures
// (docs/architecture.md, "Simulation speed").
#include <string>

namespace surfvp {

struct BenchOptions {
    std::string scenario = "budget_1024x768";
    unsigned frames = 20;
    bool scaling = false;  // also 640x480 and 1024x1024 frames, and 10x as many frames
    std::string self;      // this executable
};

int bench_command(const BenchOptions& options);

}  // namespace surfvp
