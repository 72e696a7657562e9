#include "platform/tools/bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <utility>
#include <vector>

#include "platform/scenario/config.h"
#include "platform/scenario/run_settings.h"
#include "platform/scenario/scenario.h"
#include "platform/workload/surf_settings.h"
#include "platform/workload/workload.h"
#include "sw/surf/surf.h"

extern char** environ;

namespace surfvp {
namespace {
namespace fs = std::filesystem;

using Json = nlohmann::ordered_json;

struct Measure {
    double per_frame_s;  // wall time per simulated frame (per_frame_of)
    double startup_s;    // the process's start to the simulation's (report.json)
    double peak_rss_mb;
    double chip_ms_per_frame;  // the modelled chip's steady-state period (report.json)
    double whole_run_s;        // the process from its start to its exit, as the caller waits for it
};

// Wall time per frame in the steady state: the least-squares slope of the times the frames were
// reported at (report.json frame_wall_s) over their last three quarters, past the pipeline's
// filling, all from one process (a difference of two runs' times takes in both runs' noise). A
// workload without frames (smoke): its simulation's wall time over the frames asked for.
double per_frame_of(const Json& report, unsigned frames) {
    const std::vector<double> t = report.value("frame_wall_s", std::vector<double>{});
    const size_t first = t.size() / 4;
    if (t.size() < first + 2) return report.value("wall_time_s", 0.0) / frames;
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = first; i < t.size(); ++i) {
        const double x = double(i);
        n += 1, sx += x, sy += t[i], sxx += x * x, sxy += x * t[i];
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// One child run: its time per frame, start-up and peak resident memory (from wait4's rusage).
// `mode` is the VP's traces (none or all), or direct (direct mode, no traces).
Measure child_run(const BenchOptions& o, const std::string& mode, unsigned frames, const fs::path& out,
                  const std::vector<std::string>& sets = {}) {
    const bool direct = mode == "direct";
    std::vector<std::string> args{
        o.self, "run", resolve_scenario(o.scenario), "--quiet", "--trace", direct ? "none" : mode, "--out",
        out.string(), "--set", fmt::format("surf.frames={}", frames),
        // the simulator's speed, not the verdict's re-simulations
        "--set", "verdict.band=off", "--set", "verdict.break_even=off", "--set", "verdict.software=off"};
    if (direct) args.push_back("--direct");
    for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const auto start = std::chrono::steady_clock::now();
    if (posix_spawn(&pid, o.self.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
        throw std::runtime_error("cannot start " + o.self);
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const double whole_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!WIFEXITED(status) || WEXITSTATUS(status) > 1)
        throw ConfigError(fmt::format("bench: `surfvp run {}` failed (exit {})", o.scenario, WEXITSTATUS(status)));
    const Json report = Json::parse(std::ifstream(out / "report.json"));
    const double fps = report.value("throughput_fps", 0.0);
    return {per_frame_of(report, frames), report.value("startup_s", 0.0), usage.ru_maxrss / 1024.0,
            fps > 0 ? 1e3 / fps : 0.0, whole_s};
}

// A mode (the VP's traces, or direct) at a number of frames, with settings, and its run in each
// round.
struct Series {
    Series(std::string mode, unsigned frames, std::vector<std::string> sets = {})
        : mode(std::move(mode)), frames(frames), sets(std::move(sets)) {}
    std::string mode;
    unsigned frames;
    std::vector<std::string> sets;
    std::vector<Measure> runs;
};

constexpr size_t kRounds = 3;

// Rounds, each running every series in turn (the next round in the opposite order), so that
// series whose figures are compared (traces all over none, the VP over direct) are measured in
// the same minutes: a change in the machine's speed between them cannot pass for a difference
// of the simulator's.
void measure_together(const BenchOptions& o, std::vector<Series>& series, const fs::path& out) {
    for (size_t round = 0; round < kRounds; ++round)
        for (size_t k = 0; k < series.size(); ++k) {
            Series& s = series[round % 2 ? series.size() - 1 - k : k];
            s.runs.push_back(child_run(o, s.mode, s.frames, out, s.sets));
        }
}

// Wall per frame (the fastest round's: on a shared machine the slower ones only add noise from
// elsewhere), start-up and peak memory; the VP's also the chip's time per frame and the
// real-time factor (direct mode has no time).
Json figures_of(const Series& s) {
    double per_frame = s.runs[0].per_frame_s, startup = s.runs[0].startup_s, whole = s.runs[0].whole_run_s, peak = 0;
    Json rounds = Json::array();  // each round's own, for the spread (and the ratios)
    for (const Measure& m : s.runs) {
        per_frame = std::min(per_frame, m.per_frame_s);
        startup = std::min(startup, m.startup_s);
        whole = std::min(whole, m.whole_run_s);
        peak = std::max(peak, m.peak_rss_mb);
        rounds.push_back(m.per_frame_s * 1e3);
    }
    Json figures = {{"wall_per_frame_ms", per_frame * 1e3},
                    {"per_round_ms", rounds},
                    {"startup_ms", startup * 1e3},
                    {"whole_run_ms", whole * 1e3},
                    {"peak_rss_mb", peak}};
    if (s.mode == "direct") return figures;
    const double chip_ms = s.runs[0].chip_ms_per_frame;
    figures["chip_ms_per_frame"] = chip_ms;
    figures["real_time_factor"] = per_frame > 0 ? chip_ms / (per_frame * 1e3) : 0.0;
    return figures;
}

// One series' time (per frame, or another Measure field) over another's: the median of the
// rounds' own ratios, each taken from runs seconds apart (a slow spell of the machine moves
// both sides).
double ratio_by_round(const Series& a, const Series& b, double Measure::*time = &Measure::per_frame_s) {
    std::vector<double> ratios;
    for (size_t round = 0; round < kRounds; ++round)
        ratios.push_back(b.runs[round].*time > 0 ? a.runs[round].*time / b.runs[round].*time : 0.0);
    std::sort(ratios.begin(), ratios.end());
    return ratios[kRounds / 2];
}

// The float reference SURF (sw/surf at its defaults, one thread) on the scenario's first frame
// as the chip takes it, at the scenario's keypoint budget: the median of 5 detect-and-describe
// calls, milliseconds.
Json reference_time(const std::string& scenario) {
    const Config c = load_scenario(resolve_scenario(scenario), {});
    cv::Mat frame;
    for_each_chip_frame(c, [&](size_t i, const cv::Mat& f) {
        if (i == 0) frame = f.clone();
    });
    surf::Params p;
    p.threads = 1;
    const int target = int(surf_settings(c).target_keypoints);
    if (target > 0) p.threshold = surf::threshold_for_count(frame, target, p);
    std::vector<double> ms;
    size_t keypoints = 0;
    for (int k = 0; k < 5; ++k) {
        const auto start = std::chrono::steady_clock::now();
        keypoints = surf::detect_and_describe(frame, p).size();
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(ms.begin(), ms.end());
    return {{"ms_per_frame", ms[2]}, {"keypoints", keypoints}, {"width", frame.cols}, {"height", frame.rows}};
}

}  // namespace

int bench_command(const BenchOptions& o) {
    if (o.frames == 0) throw ConfigError("--frames must be above zero");
    const Config config = load_scenario(resolve_scenario(o.scenario), {});  // bad input is reported before any run
    const fs::path out = fs::temp_directory_path() / fmt::format("surfvp_bench_{}", ::getpid());
    Json result = {{"scenario", o.scenario}, {"frames", o.frames}};
    const bool surf = run_settings(config).workload == "surf";  // direct mode runs SURF only
    std::vector<Series> compared{{"none", o.frames}, {"all", o.frames}};
    if (surf) compared.emplace_back("direct", o.frames);
    measure_together(o, compared, out);
    const Json none = figures_of(compared[0]), all = figures_of(compared[1]);
    result["traces_none"] = none;
    result["traces_all"] = all;
    const double wall = none["wall_per_frame_ms"].get<double>();
    // The targets of docs/architecture.md ("Simulation speed"), each with whether it is met.
    auto target = [](double value, double limit, bool at_most) {
        return Json{{"value", value}, {"target", limit}, {"met", at_most ? value <= limit : value >= limit}};
    };
    result["targets"] = {
        {"wall_per_frame_ms", target(wall, 25, true)},
        {"traces_all_over_none", target(ratio_by_round(compared[1], compared[0]), 1.3, true)},
        {"startup_ms", target(none["startup_ms"].get<double>(), 150, true)},
        {"peak_rss_mb",
         target(std::max(none["peak_rss_mb"].get<double>(), all["peak_rss_mb"].get<double>()), 200, true)},
        {"real_time_factor", target(none["real_time_factor"].get<double>(), 4, false)}};
    if (surf) {
        const Json reference = reference_time(o.scenario);
        result["float_reference"] = reference;
        result["ratio_to_float_reference"] = wall / reference["ms_per_frame"].get<double>();
        const Json direct = figures_of(compared[2]);
        result["direct"] = direct;
        result["targets"]["vp_over_direct"] = target(ratio_by_round(compared[0], compared[2]), 3, false);
        // The same over whole runs, start-up, first frames and exit included: what a sweep's
        // point waits for (at N frames).
        result["targets"]["vp_over_direct_whole_run"] =
            target(ratio_by_round(compared[0], compared[2], &Measure::whole_run_s), 3, false);
    }
    if (o.scaling) {
        std::vector<Series> scaling;
        std::vector<std::string> sizes;
        for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1024, 768}, std::pair{1024, 1024}}) {
            scaling.emplace_back(
                "none", o.frames,
                std::vector<std::string>{fmt::format("surf.width={}", w), fmt::format("surf.height={}", h)});
            sizes.push_back(fmt::format("{}x{}", w, h));
        }
        scaling.emplace_back("none", 10 * o.frames);
        sizes.push_back("as the scenario");
        measure_together(o, scaling, out);
        result["scaling"] = Json::array();
        for (size_t k = 0; k < scaling.size(); ++k)
            result["scaling"].push_back(
                {{"size", sizes[k]}, {"frames", scaling[k].frames}, {"traces_none", figures_of(scaling[k])}});
    }
    std::error_code ignored;
    fs::remove_all(out, ignored);
    std::printf("%s\n", result.dump(2).c_str());
    return 0;
}

}  // namespace surfvp
