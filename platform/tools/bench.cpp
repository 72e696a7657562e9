#include "platform/tools/bench.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <vector>

#include "platform/scenario/config.h"
#include "platform/scenario/scenario.h"

extern char** environ;

namespace surfvp {
namespace {
namespace fs = std::filesystem;

struct Measure {
    double wall_s;
    double peak_rss_mb;
};

// One child run; its wall time and peak resident memory (from wait4's rusage).
Measure child_run(const BenchOptions& o, const std::string& trace, unsigned frames, const fs::path& out) {
    std::vector<std::string> args{o.self, "run", resolve_scenario(o.scenario), "--quiet", "--trace", trace,
                                  "--out", out.string(), "--set", fmt::format("surf.frames={}", frames),
                                  // the simulator's speed, not the verdict's re-simulations
                                  "--set", "verdict.band=off", "--set", "verdict.break_even=off"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = 0;
    if (posix_spawn(&pid, o.self.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
        throw std::runtime_error("cannot start " + o.self);
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!WIFEXITED(status) || WEXITSTATUS(status) > 1)
        throw ConfigError(fmt::format("bench: `surfvp run {}` failed (exit {})", o.scenario, WEXITSTATUS(status)));
    return {wall, usage.ru_maxrss / 1024.0};
}

}  // namespace

int bench_command(const BenchOptions& o) {
    if (o.frames == 0) throw ConfigError("--frames must be above zero");
    load_scenario(resolve_scenario(o.scenario), {});  // bad input is reported before any run
    const fs::path out = fs::temp_directory_path() / fmt::format("surfvp_bench_{}", ::getpid());
    nlohmann::ordered_json result = {{"scenario", o.scenario}, {"frames", o.frames}};
    for (const char* trace : {"none", "all"}) {
        const Measure shorter = child_run(o, trace, o.frames, out);
        const Measure longer = child_run(o, trace, 2 * o.frames, out);
        const double per_frame = (longer.wall_s - shorter.wall_s) / o.frames;
        result[std::string("traces_") + trace] = {{"wall_per_frame_ms", per_frame * 1e3},
                                                  {"startup_ms", (shorter.wall_s - o.frames * per_frame) * 1e3},
                                                  {"peak_rss_mb", std::max(shorter.peak_rss_mb, longer.peak_rss_mb)}};
    }
    std::error_code ignored;
    fs::remove_all(out, ignored);
    std::printf("%s\n", result.dump(2).c_str());
    return 0;
}

}  // namespace surfvp
