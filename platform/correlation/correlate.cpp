#include "platform/correlation/correlate.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "models/host/atomic_file.h"
#include "models/fhg/sequence_cache.h"
#include "platform/run/progress_line.h"
#include "platform/report/correlation.h"
#include "platform/cost/fpga_resources.h"
#include "platform/run/output_folder.h"
#include "platform/run/run.h"
#include "platform/scenario/parameters.h"
#include "platform/scenario/scenario.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"
#include "platform/catalog.h"
#include "platform/run/resimulation.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Sets = std::vector<std::pair<std::string, std::string>>;

constexpr double kClockStep = 5e6;  // the FHG clock's grid over its band, Hz

Config correlate_variant(const Config& base, const Sets& sets) { return base.with(sets, "correlate"); }

// A parameter's low, current and high values (its band), each once.
std::vector<std::string> band_values(const std::string& key, const Config& c) {
    const ParamSpec& p = *find_parameter(key);
    std::vector<std::string> out;
    for (const std::string& v : {p.band.low, c.value(key), p.band.high}) {
        const bool seen = std::any_of(out.begin(), out.end(), [&](const std::string& w) {
            return p.kind == ParamKind::choice ? v == w : parse_value(p, v) == parse_value(p, w);
        });
        if (!seen) out.push_back(v);
    }
    std::sort(out.begin(), out.end(), [&](const std::string& a, const std::string& b) {
        return p.kind == ParamKind::choice ? false : parse_value(p, a) < parse_value(p, b);
    });
    return out;
}

// The FHG clock over its band in steps, and the scenario's own.
std::vector<double> fhg_clocks(const Config& c) {
    const ParamSpec& p = *find_parameter("fhg.clock");
    std::vector<double> hz;
    for (double f = parse_value(p, p.band.low); f <= parse_value(p, p.band.high) + 1; f += kClockStep) hz.push_back(f);
    hz.push_back(fhg_params(c).clock.hz);
    std::sort(hz.begin(), hz.end());
    hz.erase(std::unique(hz.begin(), hz.end()), hz.end());
    return hz;
}

std::string mhz(double hz) { return fmt::format("{:g} MHz", hz / 1e6); }

bool within_about(double value, double stated) { return std::abs(value / stated - 1) <= paper::kAbout + 1e-12; }

// One schedule: its basic script against note 4's optimum, the block RAM it takes, or why the
// machine refuses it.
Json schedule_row(const Config& base, const Sets& sets) {
    Json row = Json::object();
    for (const auto& [key, value] : sets) row[key] = value;
    try {
        const Config c = correlate_variant(base, sets);
        Fhg::Params p = fhg_params(c);
        p.sequence.scheduler = fhg::Scheduler::basic;
        const fhg::Sequence& s = fhg::cached_sequence(p.sequence);
        const FpgaResources resources = fpga_resources(c);
        row["script_cycles"] = s.interval;
        row["block_cycles"] = Fhg::block_cycles(s, p);
        row["overhead"] = s.idle_bus_overhead();
        row["ramb36"] = resources.total.ramb36;
        row["lut_share"] = resources.total.luts / resources.lut_capacity;
        row["fits"] = resources.fits();
        // The paper's chip was built: a schedule reproduces it only on a chip that fits.
        row["reproduces_script"] = within_about(s.idle_bus_overhead(), paper::kOverhead);
        row["reproduces"] = row["reproduces_script"].get<bool>() && resources.fits();
    } catch (const std::invalid_argument& e) {
        row["refused"] = e.what();
        row["reproduces"] = false;
    }
    return row;
}

struct CorrelationPoint {
    size_t schedule;  // index into the schedules
    Sets sets;        // the frame-rate axes' values
    Json result;
};

std::string point_label(const Sets& sets) {
    std::string s;
    for (const auto& [key, value] : sets) s += (s.empty() ? "" : ", ") + key + " = " + value;
    return s;
}

// frames/s against the FHG clock at 100 keypoints for the first reproducing schedule: a line
// per CPU clock and FPU ratio, the paper's 9 to 11 frames/s shaded, the scenario's point ringed.
std::string plot(const std::vector<CorrelationPoint>& points, size_t schedule, const Sets& defaults,
                 double default_fps) {
    constexpr double W = 680, H = 420, L = 64, R = 190, T = 40, B = 48;
    double x0 = 1e300, x1 = 0, y1 = paper::kFps * (1 + paper::kAbout);
    std::map<std::string, std::vector<std::pair<double, double>>> lines;
    for (const CorrelationPoint& p : points) {
        if (p.schedule != schedule || p.result.contains("error") || p.sets[3].second != "100") continue;
        const double x = std::stod(p.sets[0].second), y = p.result["fps"].get<double>();
        x0 = std::min(x0, x), x1 = std::max(x1, x), y1 = std::max(y1, y);
        lines[fmt::format("CPU {}, FPU ratio {}", p.sets[1].second, p.sets[2].second)].push_back({x, y});
    }
    if (lines.empty()) return "";
    y1 *= 1.08;
    auto px = [&](double x) { return L + (x - x0) / std::max(1e-9, x1 - x0) * (W - L - R); };
    auto py = [&](double y) { return H - B - y / y1 * (H - T - B); };
    const double lo = paper::kFps * (1 - paper::kAbout), hi = paper::kFps * (1 + paper::kAbout);
    std::string svg = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" font-family=\"sans-serif\" "
        "font-size=\"12\">"
        "<rect width=\"100%\" height=\"100%\" fill=\"white\"/><text x=\"{2}\" y=\"22\" font-size=\"14\">frames/s "
        "against the "
        "FHG clock (100 keypoints a frame); shaded: the paper's about 10</text>"
        "<rect x=\"{2}\" y=\"{3:.1f}\" width=\"{4:.1f}\" height=\"{5:.1f}\" fill=\"#dfe9df\"/>"
        "<line x1=\"{2}\" y1=\"{6}\" x2=\"{7}\" y2=\"{6}\" stroke=\"black\"/><line x1=\"{2}\" y1=\"{8}\" x2=\"{2}\" "
        "y2=\"{6}\" "
        "stroke=\"black\"/><text x=\"{9}\" y=\"{10}\" text-anchor=\"middle\">fhg.clock (MHz)</text>",
        W, H, L, py(hi), W - L - R, py(lo) - py(hi), H - B, W - R, T, (L + W - R) / 2, H - 10);
    for (double t = 0; t <= y1; t += 2)  // frames/s in steps of 2
        svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{:g}</text>", L - 6, py(t) + 4, t);
    for (const auto& [x, y] : lines.begin()->second)
        svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{:g}</text>", px(x), H - B + 16, x);
    const char* colours[] = {"#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#76b7b2", "#b07aa1"};
    size_t k = 0;
    for (auto& [name, pts] : lines) {
        std::sort(pts.begin(), pts.end());
        std::string poly;
        for (const auto& [x, y] : pts) poly += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
        const char* colour = colours[k % 6];
        svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>", poly, colour);
        for (const auto& [x, y] : pts)
            svg += fmt::format(
                "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"{}\"><title>{}: {:.2f} frames/s at {:g} MHz</title>"
                "</circle>",
                px(x), py(y), colour, name, y, x);
        svg += fmt::format("<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>", W - R + 10, T + 16 + 18 * double(k), colour,
                           name);
        ++k;
    }
    if (default_fps > 0)
        svg += fmt::format(
            "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"7\" fill=\"none\" stroke=\"black\"><title>the scenario: "
            "{:.2f} frames/s</title></circle><text x=\"{:.1f}\" y=\"{:.1f}\">the scenario</text>",
            px(std::stod(defaults[0].second)), py(default_fps), default_fps, px(std::stod(defaults[0].second)) + 9,
            py(default_fps) + 16);
    return svg + "</svg>";
}

// The reproducing clocks of a grid row as runs: "95 to 110 MHz, 125 MHz".
std::string clock_runs(const Json& grid) {
    std::vector<std::string> runs;
    for (size_t i = 0; i < grid.size();) {
        if (!grid[i]["reproduces"].get<bool>()) {
            ++i;
            continue;
        }
        size_t j = i;
        while (j + 1 < grid.size() && grid[j + 1]["reproduces"].get<bool>()) ++j;
        const std::string first = grid[i]["fhg.clock"], last = grid[j]["fhg.clock"];
        runs.push_back(i == j ? first : first.substr(0, first.find(' ')) + " to " + last);
        i = j + 1;
    }
    std::string out;
    for (const std::string& r : runs) out += (out.empty() ? "" : ", ") + r;
    return out;
}

std::string correlate_markdown(const Json& r) {
    std::string md = fmt::format(
        "# Correlation: where the VP reproduces the paper ({})\n\nThe unknowns the paper's figures depend on, over "
        "their "
        "bands; kept where the VP reproduces the paper within its precision (docs/correlation.md): the basic script "
        "{:.1f} % to {:.1f} % over note 4's optimal state, and {:.0f} to {:.0f} frames/s at 1024x768 with around 100 "
        "keypoints, on a chip that fits the device.\n\n## The schedule: bus word, line FIFO, read buses, line "
        "groups\n\n"
        "| fhg.bus_word | fhg.line_fifo | fhg.read_buses | fhg.line_groups | basic script | over note 4's optimum | "
        "RAMB36 (of the chip) | LUTs (of the chip) | reproduces |\n|---|---|---|---|---:|---:|---:|---:|---|\n",
        r["scenario"].get<std::string>(), 100 * r["paper"]["overhead"][0].get<double>(),
        100 * r["paper"]["overhead"][1].get<double>(), r["paper"]["fps"][0].get<double>(),
        r["paper"]["fps"][1].get<double>());
    for (const Json& s : r["schedules"]) {
        if (s.contains("refused")) {
            md += fmt::format("| {} | {} | {} | {} | refused: {} | | | | no |\n", s["fhg.bus_word"].get<std::string>(),
                              s["fhg.line_fifo"].get<std::string>(), s["fhg.read_buses"].get<std::string>(),
                              s["fhg.line_groups"].get<std::string>(), s["refused"].get<std::string>());
            continue;
        }
        md += fmt::format("| {} | {} | {} | {} | {} cycles | {:.1f} % | {:g} | {:.0f} %{} | {} |\n",
                          s["fhg.bus_word"].get<std::string>(), s["fhg.line_fifo"].get<std::string>(),
                          s["fhg.read_buses"].get<std::string>(), s["fhg.line_groups"].get<std::string>(),
                          s["script_cycles"].get<int>(), 100 * s["overhead"].get<double>(), s["ramb36"].get<double>(),
                          100 * s["lut_share"].get<double>(), s["fits"].get<bool>() ? "" : " (does not fit)",
                          s["reproduces"].get<bool>()          ? "**yes**"
                          : s["reproduces_script"].get<bool>() ? "script only: does not fit"
                                                               : "no");
    }
    md +=
        "\n## The frame rate, for the schedules that reproduce the script on a chip that fits\n\nThe FHG clocks at "
        "which the rate is "
        "within "
        "the paper's precision, for each CPU clock, APU FPU ratio and keypoint count (2-frame re-simulations):\n\n"
        "| block cycles | cpu.clock | cpu.fpu_ratio | surf.target_keypoints | fhg.clock that reproduces | frames/s "
        "there |\n"
        "|---:|---|---|---|---|---|\n";
    for (const Json& g : r["region"]) {
        const bool any = !g["fhg_clocks"].empty();
        md += fmt::format(
            "| {} | {} | {} | {} | {} | {} |\n", g["block_cycles"].get<int>(), g["cpu.clock"].get<std::string>(),
            g["cpu.fpu_ratio"].get<std::string>(), g["surf.target_keypoints"].get<std::string>(),
            any ? clock_runs(g["grid"]) : "none",
            any ? fmt::format("{:.2f} to {:.2f}", g["fps"][0].get<double>(), g["fps"][1].get<double>()) : "-");
    }
    const Json& d = r["defaults"];
    md += fmt::format(
        "\n## The scenario's own values\n\n{}: basic script {:.1f} % over the optimum, {:.2f} frames/s. **{}**\n",
        d["label"].get<std::string>(), 100 * d["overhead"].get<double>(), d["fps"].get<double>(),
        d["inside"].get<bool>() ? "Inside the region: the defaults reproduce the paper."
                                : "Outside the region: " + d["why"].get<std::string>() + ".");
    if (!r["failed_points"].empty())
        md += fmt::format("\n{} points failed (correlate.json says why).\n", r["failed_points"].size());
    return md + "\n![frames/s against the FHG clock](correlate.svg)\n";
}

}  // namespace

int correlate_command(const CorrelateOptions& o) {
    const Config config = load_scenario(resolve_scenario(o.scenario), o.sets);
    if (run_settings(config).workload != "surf")
        throw ConfigError(
            fmt::format("{}: correlate needs a SURF scenario (run.workload: surf)", config.where("run.workload")));
    check_scenario(config);
    const unsigned frames = resimulation_frames(config);
    const Config reference = correlate_variant(config, {{"surf.frames", std::to_string(frames)},
                                                        {"run.parallel", "off"},
                                                        {"verdict.band", "off"},
                                                        {"verdict.break_even", "off"},
                                                        {"verdict.software", "off"}});

    // The schedules, from their sequences alone.
    Json schedules = Json::array();
    const auto& words = find_parameter("fhg.bus_word")->choices;
    const auto& fifos = find_parameter("fhg.line_fifo")->choices;
    for (const std::string& word : words)
        for (const std::string& fifo : fifos)
            for (const char* buses : {"2", "4", "6"})
                for (const char* groups : {"1", "2", "4"})
                    schedules.push_back(schedule_row(config, {{"fhg.bus_word", word},
                                                              {"fhg.line_fifo", fifo},
                                                              {"fhg.read_buses", buses},
                                                              {"fhg.line_groups", groups}}));

    // The frame rate for each block-cycle count among the reproducing schedules (the FHG's
    // timing depends on nothing else of the schedule), over the other unknowns.
    std::map<int, size_t> representative;
    for (size_t i = 0; i < schedules.size(); ++i)
        if (schedules[i]["reproduces"].get<bool>()) representative.emplace(schedules[i]["block_cycles"].get<int>(), i);
    std::vector<CorrelationPoint> points;
    const std::vector<std::string> cpus = band_values("cpu.clock", config),
                                   ratios = band_values("cpu.fpu_ratio", config);
    const std::vector<std::string> keypoints{"90", "100", "110"};  // around the paper's 100
    for (const auto& [cycles, i] : representative)
        for (double hz : fhg_clocks(config))
            for (const std::string& cpu : cpus)
                for (const std::string& ratio : ratios)
                    for (const std::string& kp : keypoints)
                        points.push_back({i,
                                          {{"fhg.clock", mhz(hz)},
                                           {"cpu.clock", cpu},
                                           {"cpu.fpu_ratio", ratio},
                                           {"surf.target_keypoints", kp}},
                                          {}});
    const Sets schedule_keys = config.sets_of({"fhg.bus_word", "fhg.line_fifo", "fhg.read_buses", "fhg.line_groups"});
    Sets defaults = config.sets_of({"cpu.clock", "cpu.fpu_ratio", "surf.target_keypoints"});
    defaults.insert(defaults.begin(), {"fhg.clock", mhz(fhg_params(config).clock.hz)});
    Json default_point;

    OutputFolder out(o.out.empty() ? fs::path("traces") / ("correlate_" + config.name) : fs::path(o.out),
                     {"correlate.json", "correlate.md", "correlate.svg"});
    Resimulation::prepare(reference);
    {
        Resimulation pool(o.jobs, out.staging() / ".points");
        for (CorrelationPoint& p : points) {
            Sets sets = p.sets;
            for (const char* key : {"fhg.bus_word", "fhg.line_fifo", "fhg.read_buses", "fhg.line_groups"})
                sets.emplace_back(key, schedules[p.schedule][key].get<std::string>());
            pool.submit(correlate_variant(reference, sets), [&p](const Json& r) { p.result = r; });
        }
        pool.submit(reference, [&](const Json& r) { default_point = r; });
        ProgressLine progress(o.quiet, "correlate", 0.0, 0.5, 5.0);
        pool.run([&](size_t done, size_t total) { progress.steps(done, total, "re-simulations"); });
    }

    // The region: per schedule and CPU-side values, the FHG clocks that reproduce the rate.
    Json region = Json::array(), failed = Json::array(), all = Json::array();
    std::map<std::string, size_t> group_of;
    for (const CorrelationPoint& p : points) {
        Json row = {{"schedule", p.schedule}};
        for (const auto& [key, value] : p.sets) row[key] = value;
        if (p.result.contains("error")) {
            row["error"] = p.result["error"];
            failed.push_back(row);
            all.push_back(row);
            continue;
        }
        const double fps = p.result["fps"].get<double>();
        row["fps"] = fps;
        row["limit"] = p.result["limit"];
        row["reproduces"] = within_about(fps, paper::kFps);
        all.push_back(row);
        const std::string key =
            fmt::format("{}|{}|{}|{}", p.schedule, p.sets[1].second, p.sets[2].second, p.sets[3].second);
        auto [it, fresh] = group_of.emplace(key, region.size());
        if (fresh)
            region.push_back({{"block_cycles", schedules[p.schedule]["block_cycles"]},
                              {"cpu.clock", p.sets[1].second},
                              {"cpu.fpu_ratio", p.sets[2].second},
                              {"surf.target_keypoints", p.sets[3].second},
                              {"fhg_clocks", Json::array()},
                              {"fps", Json::array({1e300, 0.0})},
                              {"grid", Json::array()}});
        Json& g = region[it->second];
        g["grid"].push_back({{"fhg.clock", p.sets[0].second}, {"fps", fps}, {"reproduces", row["reproduces"]}});
        if (!row["reproduces"].get<bool>()) continue;
        g["fhg_clocks"].push_back(p.sets[0].second);
        g["fps"] = {std::min(g["fps"][0].get<double>(), fps), std::max(g["fps"][1].get<double>(), fps)};
    }

    // The scenario's own point: its schedule and its rate.
    const Json own = schedule_row(config, schedule_keys);
    const double own_fps = default_point.contains("error") ? 0 : default_point.value("fps", 0.0);
    std::string why;
    if (!own["reproduces"].get<bool>())
        why = "its basic script is not about 11 % over the optimum";
    else if (!within_about(own_fps, paper::kFps))
        why = fmt::format("its rate, {:.2f} frames/s, is not about 10", own_fps);
    const Json defaults_json = {{"label", point_label(schedule_keys) + ", " + point_label(defaults)},
                                {"overhead", own.value("overhead", 0.0)},
                                {"fps", own_fps},
                                {"inside", why.empty()},
                                {"why", why}};

    Json r = {{"surfvp_version", SURFVP_VERSION},
              {"scenario", config.name},
              {"frames", frames},
              {"paper",
               {{"fps", {paper::kFps * (1 - paper::kAbout), paper::kFps * (1 + paper::kAbout)}},
                {"overhead", {paper::kOverhead * (1 - paper::kAbout), paper::kOverhead * (1 + paper::kAbout)}}}},
              {"schedules", schedules},
              {"region", region},
              {"points", all},
              {"failed_points", failed},
              {"defaults", defaults_json}};
    const fs::path staging = out.staging();
    write_file_atomically((staging / "correlate.json").string(), r.dump(2) + "\n");
    write_file_atomically((staging / "correlate.md").string(), correlate_markdown(r));
    const size_t drawn = representative.count(own.value("block_cycles", 0))
                             ? representative.at(own["block_cycles"].get<int>())
                         : representative.empty() ? 0
                                                  : representative.begin()->second;
    write_file_atomically((staging / "correlate.svg").string(), plot(points, drawn, defaults, own_fps));
    out.publish();
    if (!o.quiet)
        std::fprintf(stderr, "surfvp: correlate %s: the defaults are %s the region; %s\n", config.name.c_str(),
                     why.empty() ? "inside" : "outside", (out.folder() / "correlate.md").c_str());
    return kExitOk;
}

}  // namespace surfvp
