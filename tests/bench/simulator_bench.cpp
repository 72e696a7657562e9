// The simulator's own speed: wall time per simulated 1024x768 frame of the budget scenario,
// with traces off and all on, and the peak memory of the run. Each iteration is a child
// `surfvp run` (SystemC simulates once per process); per-frame time is the difference of a
// run of 2N and a run of N frames, divided by N, so start-up cancels out.
#include <benchmark/benchmark.h>
#include <chrono>
#include <fmt/format.h>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

struct Run {
    double wall_s;
    double peak_rss_mb;
};

Run run_frames(const std::string& trace, int frames) {
    const std::string out = fmt::format("/tmp/surfvp_simbench_{}", ::getpid());
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid == 0) {
        const std::string set = fmt::format("surf.frames={}", frames);
        execl(SURFVP_BINARY, SURFVP_BINARY, "run", SURFVP_SOURCE_DIR "/scenarios/budget_1024x768.yaml", "--quiet",
              "--trace", trace.c_str(), "--out", out.c_str(), "--set", set.c_str(), "--set", "verdict.band=off", "--set",
              "verdict.break_even=off", "--set", "verdict.software=off", nullptr);
        _exit(127);
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    return {std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), usage.ru_maxrss / 1024.0};
}

void simulate_frames(benchmark::State& state, const std::string& trace) {
    const int n = int(state.range(0));
    double peak = 0;
    for (auto _ : state) {
        const Run shorter = run_frames(trace, n), longer = run_frames(trace, 2 * n);
        const double per_frame = (longer.wall_s - shorter.wall_s) / n;
        state.SetIterationTime(per_frame);
        peak = std::max({peak, shorter.peak_rss_mb, longer.peak_rss_mb});
    }
    state.counters["peak_rss_mb"] = peak;
}

void BM_FrameTracesOff(benchmark::State& state) { simulate_frames(state, "none"); }
void BM_FrameTracesAll(benchmark::State& state) { simulate_frames(state, "all"); }

// A long run holds flat memory: peak resident memory of a run of 100 and of 1000 small frames
// (160x120, traces off). Frames stream through the buffer sets, keypoints go to their files and
// the charts' bins widen, so what still grows is the report's row per frame (about 2 KB).
void BM_LongRunMemory(benchmark::State& state) {
    const std::string frames = fmt::format("surf.frames={}", state.range(0));
    const std::string out = fmt::format("/tmp/surfvp_longbench_{}", ::getpid());
    double peak = 0;
    for (auto _ : state) {
        const pid_t pid = fork();
        if (pid == 0) {
            execl(SURFVP_BINARY, SURFVP_BINARY, "run", SURFVP_SOURCE_DIR "/scenarios/budget_1024x768.yaml", "--quiet", "--trace",
                  "none", "--out", out.c_str(), "--set", frames.c_str(), "--set", "surf.width=160", "--set", "surf.height=120",
                  "--set", "surf.target_keypoints=20", "--set", "budget.fps=0", "--set", "verdict.band=off", "--set",
                  "verdict.break_even=off", "--set", "verdict.software=off", nullptr);
            _exit(127);
        }
        int status = 0;
        rusage usage{};
        wait4(pid, &status, 0, &usage);
        peak = usage.ru_maxrss / 1024.0;
    }
    state.counters["peak_rss_mb"] = peak;
}
BENCHMARK(BM_LongRunMemory)->Arg(100)->Arg(1000)->Unit(benchmark::kSecond)->Iterations(1);

// Sweep speed (docs/sweeps.md): points per minute of `surfvp sweep` on this machine, for
// 5-frame points of the budget scenario (1024x768, traces off), two at a time; a fresh sweep
// folder each iteration, so nothing is resumed.
void BM_SweepPoints(benchmark::State& state) {
    const std::string dir = fmt::format("/tmp/surfvp_sweepbench_{}", ::getpid());
    const std::string file = dir + ".yaml";
    {
        std::FILE* f = std::fopen(file.c_str(), "w");
        std::fprintf(f, "scenario: %s/scenarios/budget_1024x768.yaml\nset: {surf.frames: 5}\n"
                        "axes:\n  fhg.clock: [100 MHz, 125 MHz, 150 MHz]\n  fhg.read_buses: [2, 4, 6, 8]\n",
                     SURFVP_SOURCE_DIR);
        std::fclose(f);
    }
    double walls = 0;
    for (auto _ : state) {
        std::system(("rm -rf " + dir).c_str());
        const auto start = std::chrono::steady_clock::now();
        const pid_t pid = fork();
        if (pid == 0) {
            execl(SURFVP_BINARY, SURFVP_BINARY, "sweep", file.c_str(), "--quiet", "--jobs", "2", "--out", dir.c_str(), nullptr);
            _exit(127);
        }
        int status = 0;
        waitpid(pid, &status, 0);
        walls += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    state.counters["points_per_minute"] = 12 * double(state.iterations()) / walls * 60;  // over every iteration
    std::system(("rm -rf " + dir + " " + file).c_str());
}
BENCHMARK(BM_SweepPoints)->Unit(benchmark::kSecond)->Iterations(5);

// Iteration time = wall time per simulated frame.
BENCHMARK(BM_FrameTracesOff)->Arg(10)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FrameTracesAll)->Arg(10)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
