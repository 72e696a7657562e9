// The simulator's own speed against issue 14's targets: wall time per simulated 1024x768
// frame of the budget scenario with traces off (25 ms) and all on (1.3x off), start-up
// (150 ms), peak memory (200 MB), the real-time factor (4) and direct mode (3x the VP). Each
// iteration is a child `surfvp run` (SystemC simulates once per process); per-frame time is
// the run's own simulation wall time (report.json wall_time_s) over its frames, start-up its
// startup_s (process start to simulation start), so neither includes the other.
#include <benchmark/benchmark.h>
#include <chrono>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace {

constexpr int kFrames = 20;

struct Run {
    double wall_s;  // the whole process
    double peak_rss_mb;
    nlohmann::json report;
};

// `surfvp run` of the budget scenario (verdict re-simulations off) with `extra` arguments.
Run run_budget(const std::vector<std::string>& extra, int frames = kFrames) {
    const std::string out = fmt::format("/tmp/surfvp_simbench_{}", ::getpid());
    std::vector<std::string> args{SURFVP_BINARY,
                                  "run",
                                  std::string(SURFVP_SOURCE_DIR) + "/scenarios/budget_1024x768.yaml",
                                  "--quiet",
                                  "--out",
                                  out,
                                  "--set",
                                  fmt::format("surf.frames={}", frames),
                                  "--set",
                                  "verdict.band=off",
                                  "--set",
                                  "verdict.break_even=off",
                                  "--set",
                                  "verdict.software=off"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid == 0) {
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        execv(SURFVP_BINARY, argv.data());
        _exit(127);
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ifstream in(out + "/report.json");
    if (!WIFEXITED(status) || WEXITSTATUS(status) > 1 || !in) {
        std::fprintf(stderr, "simulator_bench: surfvp run failed (status %d)\n", status);
        std::exit(1);
    }
    return {wall, usage.ru_maxrss / 1024.0, nlohmann::json::parse(in)};
}

// Iteration time: wall time per simulated frame.
void simulate_frames(benchmark::State& state, const std::string& trace) {
    double peak = 0, startup = 0, factor = 0;
    for (auto _ : state) {
        const Run r = run_budget({"--trace", trace});
        state.SetIterationTime(r.report["wall_time_s"].get<double>() / kFrames);
        peak = std::max(peak, r.peak_rss_mb);
        startup = r.report["startup_s"].get<double>() * 1e3;
        factor = r.report["real_time_factor"].get<double>();
    }
    state.counters["peak_rss_mb"] = peak;
    state.counters["startup_ms"] = startup;
    state.counters["real_time_factor"] = factor;
}

void BM_FrameTracesOff(benchmark::State& state) { simulate_frames(state, "none"); }
void BM_FrameTracesAll(benchmark::State& state) { simulate_frames(state, "all"); }

// Iteration time: start-up (load, calibrate, generate the sequence, elaborate), warm caches.
void BM_StartUp(benchmark::State& state) {
    for (auto _ : state) state.SetIterationTime(run_budget({"--trace", "none"}).report["startup_s"].get<double>());
}

// Iteration time: a direct-mode run's whole process per frame; vp_over_direct is the VP's
// whole process over it (both with their start-up).
void BM_DirectMode(benchmark::State& state) {
    double vp = 0, direct = 0;
    for (auto _ : state) {
        const double d = run_budget({"--direct"}).wall_s;
        vp += run_budget({"--trace", "none"}).wall_s;
        direct += d;
        state.SetIterationTime(d / kFrames);
    }
    state.counters["vp_over_direct"] = vp / direct;
}

// fhg.model=rtl on whole frames: the verilated datapath computes and times every block row of
// three 1024x768 budget frames. Iteration time: its wall time per frame; rtl_over_model is that
// over the model's, and same_fps is 1 when both report the same frame rate and FHG figures (the test suite
// checks every figure on 320x240 frames: tests/platform/rtl_model_test.cpp).
void BM_FrameFhgRtl(benchmark::State& state) {
    constexpr int kRtlFrames = 3;
    double model = 0, rtl = 0;
    bool same = true;
    for (auto _ : state) {
        const Run m = run_budget({"--trace", "none"}, kRtlFrames);
        const Run r = run_budget({"--trace", "none", "--set", "fhg.model=rtl"}, kRtlFrames);
        model += m.report["wall_time_s"].get<double>();
        rtl += r.report["wall_time_s"].get<double>();
        same = same && m.report["throughput_fps"] == r.report["throughput_fps"] && m.report["fhg"] == r.report["fhg"];
        state.SetIterationTime(r.report["wall_time_s"].get<double>() / kRtlFrames);
    }
    state.counters["rtl_over_model"] = rtl / model;
    state.counters["same_fps"] = same;
}
BENCHMARK(BM_FrameFhgRtl)->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);

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
            execl(SURFVP_BINARY, SURFVP_BINARY, "run", SURFVP_SOURCE_DIR "/scenarios/budget_1024x768.yaml", "--quiet",
                  "--trace", "none", "--out", out.c_str(), "--set", frames.c_str(), "--set", "surf.width=160", "--set",
                  "surf.height=120", "--set", "surf.target_keypoints=20", "--set", "budget.fps=0", "--set",
                  "verdict.band=off", "--set", "verdict.break_even=off", "--set", "verdict.software=off", nullptr);
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
        std::fprintf(f,
                     "scenario: %s/scenarios/budget_1024x768.yaml\nset: {surf.frames: 5}\n"
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
            execl(SURFVP_BINARY, SURFVP_BINARY, "sweep", file.c_str(), "--quiet", "--jobs", "2", "--out", dir.c_str(),
                  nullptr);
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

BENCHMARK(BM_FrameTracesOff)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FrameTracesAll)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_StartUp)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_DirectMode)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
