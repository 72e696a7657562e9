#include "platform/cli/run_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>

#include "models/host/atomic_file.h"
#include "platform/compare/compare.h"
#include "platform/catalog.h"
#include "platform/cost/clock_closure.h"
#include "platform/cost/fpga_resources.h"
#include "platform/report/report.h"
#include "platform/report/run_summary.h"
#include "platform/run/output_folder.h"
#include "platform/run/run.h"
#include "platform/scenario/consistency.h"
#include "platform/scenario/scenario.h"
#include "platform/soc.h"
#include "platform/verdict/verdict.h"

namespace surfvp {
namespace fs = std::filesystem;
namespace {

fs::path output_path(const RunOptions& options, const Config& config) {
    return options.out.empty() ? fs::path("traces") / config.name : fs::path(options.out);
}

// The last line, from the report as it was published: passed, FAILED or BROKEN, the answer as
// report.md's first line gives it (the verdict, or the frame rate against the budget and the
// limit), and the whole wall time, the verdict's re-simulations included.
void print_summary(const Config& config, const fs::path& dir, bool direct, double wall_s) {
    const auto report = nlohmann::ordered_json::parse(std::ifstream(dir / "report.json"));
    const RunSummary r = RunSummary::of(report);
    const char* verdict = r.result();
    const std::string answer = answer_line(report);
    if (direct) {
        std::fprintf(stderr, "surfvp: %s (direct): %s%s in %.1f s wall; report in %s\n", config.name.c_str(), verdict,
                     r.broken ? (": " + answer + ";").c_str() : "", wall_s, (dir / "report.json").c_str());
        return;
    }
    std::fprintf(stderr, "surfvp: %s: %s%s; %.3f ms simulated, %.1f s wall in all; report in %s\n", config.name.c_str(),
                 verdict, answer.empty() ? "" : (": " + answer).c_str(), r.sim_time_s * 1e3, wall_s,
                 (dir / "report.md").c_str());
}

// --quick: the scenario as one run, without the verdict's re-simulations. config.yaml says
// "--quick" beside each setting it turned off; a --set that turns one on contradicts it.
void make_quick(Config& config) {
    const VerdictSettings asked = verdict_settings(config);
    for (const auto& [key, on] :
         {std::pair{"verdict.break_even", asked.break_even}, std::pair{"verdict.band", asked.band},
          std::pair{"verdict.software", asked.software}}) {
        if (on && config.origin(key) == "--set")
            throw ConfigError(
                fmt::format("--quick runs the scenario without the verdict's re-simulations, but --set "
                            "{}=on asks for one: give one or the other",
                            key));
        config.set(key, "off", "--quick");
    }
    for (const Ineffective& i : ineffective_parameters(config)) config.note(i.key, i.reason);
}

void print_warnings(const Config& config) {
    for (const std::string& w : scenario_warnings(config)) std::fprintf(stderr, "surfvp: warning: %s\n", w.c_str());
    const FpgaResources fpga = fpga_resources(config);
    if (!fpga.fits())
        std::fprintf(stderr,
                     "surfvp: warning: the configuration does not fit the %s: %s; a run misses its goal "
                     "(docs/resources.md)\n",
                     fpga.device.c_str(), fmt::format("{}", fmt::join(fpga.over, "; ")).c_str());
    const ClockClosure closure = clock_closure(config);
    if (!closure.closes())
        std::fprintf(stderr,
                     "surfvp: warning: the configuration does not close its clocks: %s; a run misses its goal "
                     "(docs/resources.md)\n",
                     fmt::format("{}", fmt::join(closure.failing, "; ")).c_str());
}

}  // namespace

int run_scenario(const RunOptions& options) {
    const auto began = std::chrono::steady_clock::now();
    // The run's threads are its own (run.parallel): OpenCV's pool, which its first resize would
    // start (~1 ms), would only compete with them.
    cv::setNumThreads(0);
    Config config = load_scenario(resolve_scenario(options.scenario), options.sets);
    if (options.quick) make_quick(config);
    trace_options(options.trace, "");  // a bad --trace is bad input before anything is written
    if (options.direct && !config.faults.empty())
        throw ConfigError(
            fmt::format("{}: faults: --direct has no time, buses or interrupts to inject them into; "
                        "run without --direct",
                        config.faults.front().origin));
    check_scenario(config);
    if (!options.compare_to.empty()) check_side(options.compare_to);
    print_warnings(config);
    // The names a run writes at the folder's top: a folder of the user's under one is refused
    // before anything is simulated.
    static const std::set<std::string> outputs = {
        "keypoints",       "report.json",         "report.md",    "report.html", "config.yaml",
        "frames.csv",      "tornado.svg",         "trace.vcd",    "trace.gtkw",  "trace.perfetto.json",
        "trace.tasks.txt", "trace.cpu.phase.txt", "compare.json", "compare.md"};
    OutputFolder out(output_path(options, config), outputs);
    const std::string staging = out.staging().string();
    int code = kExitOk;
    try {
        if (options.direct)
            code = run_direct(config, staging);
        else if (verdict_requested(config))
            code = run_with_verdict(config, staging, options.trace, options.quiet);
        else
            code = write_run(config, staging, simulate_scenario(config, staging, options.trace, options.quiet));
        if (!options.compare_to.empty()) write_comparison(options.compare_to, staging, out.folder().string());
        out.publish();
    } catch (const EnvironmentError& e) {
        throw EnvironmentError(fmt::format("{}; what was in {} before this run is as it was",
                                           out.as_published(e.what()), out.folder().string()));
    }
    if (!options.quiet)
        print_summary(config, out.folder(), options.direct,
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count());
    return code;
}

int validate_scenario(const RunOptions& options) {
    const std::string path = resolve_scenario(options.scenario);
    const Config config = load_scenario(path, options.sets);
    check_scenario(config);
    Tracer tracer;  // elaborate with every trace off: catches what only the wiring can see
    Soc soc(config, tracer);
    print_warnings(config);
    size_t from_file = 0, from_set = 0;
    for (const auto& e : config.entries()) {
        if (e.origin == "--set")
            ++from_set;
        else if (e.origin != "default")
            ++from_file;
    }
    std::printf("%s: ok: scenario '%s', %zu parameters (%zu from the file, %zu from --set, the rest defaults)\n",
                path.c_str(), config.name.c_str(), config.entries().size(), from_file, from_set);
    return kExitOk;
}

}  // namespace surfvp
