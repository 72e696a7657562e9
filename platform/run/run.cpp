#include "platform/run/run.h"

#include "platform/cost/clock_closure.h"
#include "platform/cost/power.h"
#include "platform/report/correlation.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <unistd.h>
#include <ctime>
#include <sstream>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "models/common/zeroed_memory.h"
#include "models/fhg/hessian_core.h"
#include "models/fhg/sequence_cache.h"
#include "platform/direct/direct_chip.h"
#include "platform/workload/frame_limits.h"
#include "platform/run/progress_line.h"
#include "platform/run/sanitizer_stacks.h"
#include "platform/report/report.h"
#include "platform/report/report_html.h"
#include "platform/report/statistics_json.h"
#include "platform/report/schedule_figures.h"
#include "platform/scenario/consistency.h"
#include "platform/scenario/run_settings.h"
#include "platform/scenario/scenario.h"
#include "platform/soc.h"

namespace surfvp {
namespace fs = std::filesystem;
namespace {

using WallClock = std::chrono::steady_clock;

// Seconds since this process started, as the kernel recorded it (/proc/self/stat's start time,
// in clock ticks since boot, against CLOCK_BOOTTIME): what start-up costs, the dynamic loader
// included; 0 where /proc cannot tell. Resolution: one clock tick (10 ms).
double process_age_s() {
    std::ifstream stat("/proc/self/stat");
    std::string text;
    std::getline(stat, text);
    const size_t close = text.rfind(')');  // the command name may hold spaces
    if (close == std::string::npos) return 0;
    std::istringstream fields(text.substr(close + 2));
    std::string field;
    for (int i = 3; i < 22 && fields >> field;) ++i;  // field 22: starttime
    unsigned long long ticks = 0;
    if (!(fields >> ticks)) return 0;
    timespec now{};
    clock_gettime(CLOCK_BOOTTIME, &now);
    return double(now.tv_sec) + now.tv_nsec * 1e-9 - double(ticks) / double(sysconf(_SC_CLK_TCK));
}

double since(WallClock::time_point start) { return std::chrono::duration<double>(WallClock::now() - start).count(); }

}  // namespace

Tracer::Options trace_options(const std::string& mode, const std::string& dir) {
    if (mode != "none" && mode != "vcd" && mode != "perfetto" && mode != "all")
        throw ConfigError(fmt::format("--trace {}: expected none, vcd, perfetto or all", mode));
    return {mode == "vcd" || mode == "all", mode == "perfetto" || mode == "all", dir};
}

namespace {

// The run's checks, and whether it passed (every check held, the software ran to its end) or
// broke (the software failed, or a check of the run itself, not of a goal, did not hold).
void record_checks(nlohmann::ordered_json& r, const std::vector<Check>& checks, const std::string& failure) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    bool passed = failure.empty(), broken = !failure.empty();
    for (const Check& c : checks) {
        list.push_back(
            {{"name", c.name}, {"passed", c.passed}, {"kind", c.goal ? "goal" : "run"}, {"detail", c.detail}});
        passed = passed && c.passed;
        broken = broken || (!c.passed && !c.goal);
    }
    r["passed"] = passed;
    r["broken"] = broken;
    if (!failure.empty()) r["failure"] = failure;
    r["checks"] = list;
}

// The chip must have been buildable (the paper's was): it fits the device with the placement
// margin kept, and closes every clock. Goals: a configuration that misses them is the
// design's answer (exit 1), first in the report.
std::vector<Check> buildability_checks(const FpgaResources& resources, const ClockClosure& closure) {
    return {
        {"fits the FPGA", resources.fits(),
         resources.fits() ? fmt::format("{:.0f} % of the LUTs, {:.0f} % of the RAMB36 of the {}",
                                        100 * resources.total.luts / resources.lut_capacity,
                                        100 * resources.total.ramb36 / resources.ramb36_capacity, resources.device)
                          : fmt::format("does not fit the {}: {}", resources.device, fmt::join(resources.over, "; ")),
         true},
        {"closes its clocks", closure.closes(),
         closure.closes() ? fmt::format("{} clock domains under their maximum", closure.domains.size())
                          : fmt::format("does not close: {}", fmt::join(closure.failing, "; ")),
         true}};
}

struct Outcome {
    sc_core::sc_time sim_time;
    std::string failure;  // empty when the software ran to its end
};

// Simulates in slices until the software returns, a stall, or run.max_time.
Outcome simulate(Soc& soc, const Config& config, ProgressLine& progress) {
    const Duration max_time = run_settings(config).max_time;
    const sc_core::sc_time limit(double(max_time.ps), sc_core::SC_PS);
    const sc_core::sc_time slice(100, sc_core::SC_US);
    sc_core::sc_spawn_options pause_when_done;
    pause_when_done.spawn_method();
    pause_when_done.dont_initialize();
    pause_when_done.set_sensitivity(&soc.cpu().done_event());
    sc_core::sc_spawn([] { sc_core::sc_pause(); }, "pause_when_software_done", &pause_when_done);

    while (!soc.cpu().finished()) {
        if (sc_core::sc_time_stamp() >= limit)
            return {sc_core::sc_time_stamp(),
                    fmt::format("the software had not finished after run.max_time ({})", format_duration(max_time))};
        if (sc_core::sc_time_stamp() > sc_core::SC_ZERO_TIME && !sc_core::sc_pending_activity())
            return {sc_core::sc_time_stamp(),
                    "stalled: nothing is left to simulate but the software has not finished "
                    "(is it waiting for an interrupt that never comes?)"};
        sc_core::sc_start(slice);
        back_on_main_stack();
        const Progress p = soc.workload().progress();
        const double sim_s = sc_core::sc_time_stamp().to_seconds();
        progress.steps(p.done, p.total, p.unit, false, fmt::format(", {:.1f} ms simulated", sim_s * 1e3));
    }
    if (!soc.cpu().error().empty()) return {soc.cpu().finish_time(), "software error: " + soc.cpu().error()};
    return {soc.cpu().finish_time(), ""};
}

nlohmann::ordered_json build_report(const Config& config, Soc& soc, const Outcome& outcome, double startup_s,
                                    double wall_s, const std::vector<std::string>& outputs) {
    const double sim_s = outcome.sim_time.to_seconds();
    const uint64_t transactions = soc.bus_transactions();
    nlohmann::ordered_json r;
    r["surfvp_version"] = SURFVP_VERSION;
    r["scenario"] = {{"name", config.name}, {"file", config.file}, {"description", config.description}};
    const FpgaResources resources = fpga_resources(config);
    const ClockClosure closure = clock_closure(config);
    std::vector<Check> checks = soc.workload().checks();
    for (const Check& c : buildability_checks(resources, closure)) checks.push_back(c);
    record_checks(r, checks, outcome.failure);
    r["budget"] = nullptr;  // unless the workload's summary sets one
    r["sim_time_s"] = sim_s;
    r["startup_s"] = startup_s;  // from the process's start to the simulation's
    r["wall_time_s"] = wall_s;   // the simulation
    r["real_time_factor"] = wall_s > 0 ? sim_s / wall_s : 0.0;
    r["transactions"] = transactions;
    r["transactions_per_second"] = wall_s > 0 ? transactions / wall_s : 0.0;
    r["wall_clock_fields"] = {"startup_s", "wall_time_s", "real_time_factor", "transactions_per_second"};
    // How many TLM transactions carried the traffic depends on the simulation settings
    // (run.dma_granularity), not on the chip: every other figure does not.
    r["simulation_fields"] = {"transactions"};
    const nlohmann::ordered_json summary = soc.workload().summary();
    for (const auto& [key, value] : summary.items()) r[key] = value;
    if (r.contains("frame_wall_s")) r["wall_clock_fields"].push_back("frame_wall_s");
    const nlohmann::ordered_json platform = statistics_tree(soc.statistics(), sim_s);
    for (const auto& [key, value] : platform.items()) r[key] = value;
    r["statistics"] = statistics_legend(soc.statistics());
    // The FHG's schedules come from its parameters, not from the run: seqgen's figures.
    nlohmann::ordered_json& fhg = r["fhg"];
    for (size_t k = 0; k < soc.fhgs().size(); ++k)
        (fhg.is_array() ? fhg[k] : fhg)["schedules"] = schedule_figures(soc.fhgs()[k]->params());
    if (summary.contains("frames_done") && summary["frames_done"].get<size_t>() > 1) add_limits(r, config);
    r["fpga_resources"] = resources_json(resources);
    r["clock_closure"] = closure_json(closure);
    r["power"] = power_estimate(config, r, resources);
    r["power"]["band"] = cost_band(config, r);
    if (run_settings(config).workload == "surf") r["correlation"] = correlation_json(r);
    r["workload"] = soc.workload().report();
    r["outputs"] = outputs;
    return r;
}

// config.yaml: the parameters as given, and what the run used in place of one (the threshold
// surf.target_keypoints calibrated, or libSSA2's keypoint-count control chose per frame).
Config config_as_run(const Config& config, const nlohmann::ordered_json& report) {
    Config out = config;
    if (report.contains("threshold_rule") && report["threshold_rule"] != "surf.threshold")
        out.set_effect("surf.threshold", fmt::format("not used: {:.6g} instead, {}", report["threshold"].get<double>(),
                                                     report["threshold_rule"].get<std::string>()));
    return out;
}

// A model's own refusal names its fields ("fhg precision: det_frac_bits must not exceed 2 x
// response_frac_bits"): add where each of those parameters came from.
std::string with_origins(const Config& config, const std::string& message) {
    std::vector<std::string> origins;
    auto word_at = [&](size_t at, size_t length) {
        auto inside = [&](size_t i) {
            return i < message.size() && (std::isalnum((unsigned char)message[i]) || message[i] == '_');
        };
        return (at == 0 || !inside(at - 1)) && !inside(at + length);
    };
    for (const Config::Entry& e : config.entries()) {
        const std::string& key = e.spec->key;
        const std::string section = key.substr(0, key.find('.')), name = key.substr(key.find('.') + 1);
        const size_t full = message.find(key), bare = message.find(name);
        const bool named = (full != std::string::npos && word_at(full, key.size())) ||
                           (message.rfind(section, 0) == 0 && bare != std::string::npos && word_at(bare, name.size()));
        if (named) origins.push_back(fmt::format("{} = {} from {}", key, e.value, config.source_of(key)));
    }
    return origins.empty() ? message : fmt::format("{} ({})", message, fmt::join(origins, "; "));
}

}  // namespace

// The same driver and software without SystemC: keypoints, no time.
int run_direct(const Config& config, const fs::path& dir) {
    const auto workload = make_workload(config);
    DirectChip chip(config, run_settings(config).accelerators);
    const WorkerLoan loan(*workload, chip.worker());  // ends before the chip (its memory and worker) goes
    workload->attach_memory([&chip](uint64_t address, uint64_t bytes) { return chip.backdoor(address, bytes); });
    workload->write_into(dir.string());
    const double startup_s = process_age_s();
    const auto start = WallClock::now();
    std::string failure;
    try {
        workload->software()(chip);
    } catch (const OutOfMemory&) {  // not the software's failure: the machine's
        throw;
    } catch (const std::bad_alloc&) {
        throw OutOfMemory("the driver and software stage of the direct run");
    } catch (const std::exception& e) {
        failure = std::string("software error: ") + e.what();
    }
    const double wall_s = since(start);
    std::vector<Check> checks = workload->checks();
    checks.erase(std::remove_if(checks.begin(), checks.end(),
                                [](const Check& c) { return c.name == "frame-rate budget"; }),  // no time here
                 checks.end());
    std::vector<std::string> outputs{"report.json", "config.yaml"};
    for (const std::string& f : workload->files_written()) outputs.push_back(f);
    nlohmann::ordered_json r;
    r["surfvp_version"] = SURFVP_VERSION;
    r["mode"] = "direct";
    r["scenario"] = {{"name", config.name}, {"file", config.file}, {"description", config.description}};
    record_checks(r, checks, failure);
    const nlohmann::ordered_json summary = workload->summary();  // what has a meaning without time
    for (const char* key : {"image", "frames", "frames_done", "keypoints_per_frame", "keypoints_per_frame_range",
                            "threshold", "threshold_rule", "frame_wall_s"})
        if (summary.contains(key)) r[key] = summary[key];
    r["software_cycles"] = chip.cycles_consumed();
    r["startup_s"] = startup_s;  // from the process's start to the software's (as the VP's)
    r["wall_time_s"] = wall_s;   // the software's run on the chip's behaviour
    r["wall_clock_fields"] = {"startup_s", "wall_time_s", "frame_wall_s"};
    r["workload"] = workload->report();
    r["outputs"] = outputs;
    write_file_atomically((dir / "config.yaml").string(), config_as_run(config, r).to_yaml());
    write_file_atomically((dir / "report.json").string(), r.dump(2) + "\n");
    return exit_code_of(r);
}

nlohmann::ordered_json simulate_scenario(const Config& config, const std::string& out, const std::string& trace,
                                         bool quiet) {
    const Tracer::Options traces = trace_options(trace, out);
    Tracer tracer(traces);
    Soc soc(config, tracer);
    soc.workload().attach_memory(
        [&soc](uint64_t address, uint64_t bytes) { return soc.memory().backdoor(address, bytes); });
    if (!out.empty()) soc.workload().write_into(out);

    const double startup_s = process_age_s();
    const auto start = WallClock::now();
    Outcome outcome;
    {
        ProgressLine progress(quiet, config.name, 1.0, 0.5, 0.5);  // a line once a run has taken a second
        outcome = simulate(soc, config, progress);
    }
    const double wall_s = since(start);
    soc.workload().trace(tracer);

    std::vector<std::string> outputs{"report.json", "report.md", "config.yaml"};
    for (const std::string& f : tracer.finish()) outputs.push_back(fs::path(f).filename().string());
    for (const std::string& f : soc.workload().files_written()) outputs.push_back(f);
    nlohmann::ordered_json report = build_report(config, soc, outcome, startup_s, wall_s, outputs);
    if (!out.empty()) report["figures"]["first_frame_svg"] = soc.workload().first_frame_svg();  // for report.html only
    return report;
}

int write_run(const Config& config, const std::string& out, const nlohmann::ordered_json& run_report) {
    const fs::path dir(out);
    nlohmann::ordered_json report = run_report;
    if (report.contains("workload") && report["workload"].contains("per_frame")) {
        write_file_atomically((dir / "frames.csv").string(), frames_csv(report["workload"]["per_frame"]));
        report["outputs"].push_back("frames.csv");
    }
    // The pictures go into report.html, not into report.json.
    const nlohmann::ordered_json figures = report.value("figures", nlohmann::ordered_json::object());
    report.erase("figures");
    report["outputs"].push_back("report.html");
    write_file_atomically((dir / "config.yaml").string(), config_as_run(config, report).to_yaml());
    write_file_atomically((dir / "report.html").string(), report_html(report, figures));
    write_file_atomically((dir / "report.md").string(), report_markdown(report));
    write_file_atomically((dir / "report.json").string(), report.dump(2) + "\n");
    return exit_code_of(report);
}

int exit_code_of(const nlohmann::ordered_json& report) {
    if (report.value("broken", false)) return kExitBroken;
    return report.at("passed").get<bool>() ? kExitOk : kExitFailed;
}

void check_scenario(const Config& config) {
    check_consistency(config);
    check_surf_inputs(config);
    try {
        const Fhg::Params fhg = fhg_params(config);
        const fhg::HessianCore precision(fhg.precision);  // the FHG's fixed-point formats
        fhg::cached_sequence(fhg.sequence);               // its read sequence (the FHG takes it from the cache)
        make_workload(config);  // what the workload checks as it is made (its buffers in memory)
    } catch (const std::invalid_argument& e) {
        throw ConfigError(with_origins(config, e.what()));
    }
}

}  // namespace surfvp
