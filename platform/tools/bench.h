#pragma once
// `surfvp bench`: how fast the simulator runs a scenario, with traces off and all on.
// SystemC simulates once per process, so each measurement is a child `surfvp run`; the
// wall time per frame is the difference between runs of N and 2N frames, divided by N
// (start-up, i.e. loading, calibration and the sequence generator, cancels out).
#include <string>

namespace surfvp {

struct BenchOptions {
    std::string scenario = "budget_1024x768";
    unsigned frames = 10;
    std::string self;  // this executable
};

int bench_command(const BenchOptions& options);

}  // namespace surfvp
