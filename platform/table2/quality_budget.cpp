#include "platform/table2/quality_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "platform/run/output_folder.h"
#include "platform/run/progress_line.h"
#include "platform/run/resimulation.h"
#include "platform/scenario/scenario.h"
#include "platform/sweep/sweep_plan.h"
#include "platform/table2/columns.h"
#include "platform/table2/precision_axis.h"
#include "platform/table2/quality_budget_report.h"
#include "platform/workload/surf_settings.h"

namespace surfvp {
namespace {
using namespace table2;
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// The CPU stage's software settings that change what it computes (docs/quality_budget.md):
// the paper's values first. Filter sizes and octaves are the FHG's, not the software's.
std::vector<PrecisionAxis> software_axes() {
    return {{"surf.max_offset", {"0.5", "0.75", "1"}},
            {"surf.haar", {"rounded", "exact"}},
            {"surf.upright", {"off", "on"}},
            {"surf.descriptor", {"surf", "msurf"}},
            {"surf.target_keypoints", {"100", "150", "200"}}};
}

struct BudgetStudy {
    Config budget;
    std::vector<Config> sequences;  // the first `tuned` are chosen on, the rest held out
    size_t tuned = 0;
    std::optional<Config> pair;
};

Config load_one(const std::string& name, const std::vector<std::string>& sets, const std::string& role) {
    Config c = load_scenario(resolve_scenario(name), sets);
    if (c.choice("run.workload") != "surf")
        throw ConfigError(fmt::format("{}: {} {}: the quality budget needs SURF scenarios (run.workload: surf)",
                                      c.where("run.workload"), role, name));
    check_scenario(c);
    if (!c.faults.empty())  // the chip's quality runs simulate no time, where no fault can strike
        throw ConfigError(
            fmt::format("{}: {} {}: faults: give a scenario without faults", c.faults.front().origin, role, name));
    return c;
}

BudgetStudy load_budget_study(const QualityBudgetOptions& o) {
    BudgetStudy s{load_one(o.budget, o.sets, "budget scenario"), {}, 0, std::nullopt};
    if (s.budget.real("budget.fps") <= 0)
        throw ConfigError(
            fmt::format("{}: budget scenario {}: budget.fps is 0; the study prices each setting "
                        "against a frame budget",
                        s.budget.where("budget.fps"), o.budget));
    // The budget runs only give the frame rate and the CPU's time: no verdict analyses.
    apply_overrides(s.budget, kWithoutVerdictAnalyses);
    const std::vector<std::string> tuned =
        o.sequences.empty() ? std::vector<std::string>{"castle_sequence", "vtest_sequence"} : o.sequences;
    const std::vector<std::string> held = o.held_out.empty() ? std::vector<std::string>{"castel_sequence"} : o.held_out;
    for (const auto* names : {&tuned, &held})
        for (const std::string& name : *names) {
            s.sequences.push_back(load_one(name, o.sets, names == &tuned ? "--sequence" : "--held-out"));
            if (s.sequences.back().count("surf.frames") < 2)
                throw ConfigError(fmt::format("{}: sequence {} has fewer than 2 frames: no pair to score",
                                              s.sequences.back().where("surf.frames"), name));
        }
    s.tuned = tuned.size();
    if (o.pair != "none") {
        s.pair = load_one(o.pair, o.sets, "--pair");
        if (s.pair->text("eval.homography").empty())
            throw ConfigError(
                fmt::format("--pair {}: a pair under a homography (eval.homography) gives "
                            "repeatability and precision; it has none (--pair none: no pair)",
                            o.pair));
    }
    return s;
}

struct Setting {
    std::string id;
    std::vector<std::pair<std::string, std::string>> values;
    Json timing, quality;
};

// A point's sets on one scenario. Each scenario keeps its own keypoint count in proportion: a
// point asking for 1.5 times the budget scenario's keypoints gives graf 1.5 times its 1000.
Config at_point(const Config& base, const Setting& p, const Config& budget) {
    Config c = base;
    std::vector<std::string> sets;
    for (const auto& [key, value] : p.values) {
        std::string v = value;
        if (key == "surf.target_keypoints" && budget.count(key) > 0) {
            Config probe = budget;
            apply_overrides(probe, {key + "=" + value});
            v = std::to_string(
                uint64_t(std::llround(double(probe.count(key)) * double(base.count(key)) / double(budget.count(key)))));
        }
        sets.push_back(key + "=" + v);
    }
    apply_overrides(c, sets);
    return c;
}

std::vector<const Config*> study_scenarios(const BudgetStudy& s) {
    std::vector<const Config*> all{&s.budget};
    for (const Config& c : s.sequences) all.push_back(&c);
    if (s.pair) all.push_back(&*s.pair);
    return all;
}

// The scenarios as they are (the paper's software), then every combination of the axes that
// differs from it; each value checked once, each combination on every scenario, now, not after
// the first points ran.
std::vector<Setting> plan_settings(const BudgetStudy& s, const std::vector<PrecisionAxis>& axes) {
    std::set<std::pair<std::string, std::string>> changes;  // the values that change the budget scenario
    std::vector<SweepAxis> crossed;
    for (const PrecisionAxis& a : axes) {
        for (const std::string& v : a.values) try {
                Config probe = s.budget;
                apply_overrides(probe, {a.key + "=" + v});
                if (probe.value(a.key) != s.budget.value(a.key)) changes.insert({a.key, v});
            } catch (const ConfigError& e) {
                throw ConfigError(fmt::format("--axis {}={}: {}", a.key, v, e.what()));
            }
        crossed.push_back({a.key, a.values, "--axis"});
    }
    std::vector<Setting> points{{"as the scenarios are", {}, {}, {}}};
    for (SweepPoint& point : combine_axes(crossed, false, "--axis")) {
        Setting p{point.id, std::move(point.values), {}, {}};
        if (std::none_of(p.values.begin(), p.values.end(), [&](const auto& kv) { return changes.count(kv); })) continue;
        for (const Config* c : study_scenarios(s)) try {
                check_scenario(at_point(*c, p, s.budget));
            } catch (const ConfigError& e) {
                throw ConfigError(fmt::format("{}: {}: {}", p.id, c->name, e.what()));
            }
        points.push_back(std::move(p));
    }
    return points;
}

// In a child, from the budget run's report: what the setting costs.
Json timing_of(const Json& r) {
    return {{"fps", r.value("throughput_fps", 0.0)},
            {"cpu_fps", r["time_per_frame"]["cpu"].value("alone_fps", 0.0)},
            {"us_per_keypoint", r.value("software_time_per_keypoint_us", 0.0)},
            {"keypoints_per_frame", r.value("keypoints_per_frame", 0.0)},
            {"limit", r["limit"].value("resource", "")},
            {"exit", exit_code_of(r)}};
}

// In a child: the chip on every sequence and the pair, each measured.
Json score_setting(const BudgetStudy& s, const Setting& p, const std::vector<cv::Size>& pair_sizes,
                   const fs::path& scratch) {
    Json j = {{"sequences", Json::array()}, {"exit", int(kExitOk)}};
    auto keep = [&](const Column& chip, Json q) {
        q["exit"] = chip.exit_code;
        if (chip.exit_code != kExitOk && j["exit"] != kExitBroken) j["exit"] = chip.exit_code;
        return q;
    };
    for (size_t i = 0; i < s.sequences.size(); ++i) {
        const Config c = at_point(s.sequences[i], p, s.budget);
        const Column chip = fpga_column(c, scratch / fmt::format("sequence{}", i), {});
        j["sequences"].push_back(keep(chip, quality_line(chip, read_geometry(c))));
    }
    if (s.pair) {
        const Config c = at_point(*s.pair, p, s.budget);
        const Column chip = fpga_column(c, scratch / "pair", pair_sizes);
        j["pair"] = keep(chip, quality_line(chip, read_geometry(c)));
    }
    fs::remove_all(scratch);
    return j;
}

// The best float SURF (sw/surf at its defaults) on every sequence and the pair.
Json best_float(const BudgetStudy& s, std::vector<cv::Size>& pair_sizes) {
    Json j = {{"sequences", Json::array()}};
    for (const Config& c : s.sequences)
        j["sequences"].push_back(quality_line(cpu_column(c, variants(c)[0]), read_geometry(c)));
    if (s.pair) {
        const Column col = cpu_column(*s.pair, variants(*s.pair)[0]);
        pair_sizes = col.sizes;
        j["pair"] = quality_line(col, read_geometry(*s.pair));
    }
    return j;
}

void run_settings_points(const BudgetStudy& s, std::vector<Setting>& points, const std::vector<cv::Size>& pair_sizes,
                         const QualityBudgetOptions& o, const fs::path& staging) {
    for (const Config* c : study_scenarios(s)) Resimulation::prepare(*c);
    Resimulation engine(o.jobs, staging / ".points");
    for (size_t i = 0; i < points.size(); ++i) {
        engine.submit(
            at_point(s.budget, points[i], s.budget), [&points, i](const Json& r) { points[i].timing = r; }, timing_of);
        const fs::path scratch = staging / ".points" / fmt::format("point{}", i);
        engine.submit_work(
            s.budget, [&points, i](const Json& r) { points[i].quality = r; },
            [&s, p = points[i], pair_sizes, scratch](const Config&) {
                return score_setting(s, p, pair_sizes, scratch);
            });
    }
    ProgressLine progress(o.quiet, "quality-budget", 1.0, 0.5, 10.0);
    engine.run([&](size_t done, size_t total) { progress.steps(done, total, "runs"); });
}

Json study_json(const BudgetStudy& s, const std::vector<PrecisionAxis>& axes, const std::vector<Setting>& points,
                const Json& reference) {
    Json j;
    j["budget_scenario"] = s.budget.name;
    j["budget_fps"] = s.budget.real("budget.fps");
    j["sequences"] = Json::array();
    for (size_t i = 0; i < s.sequences.size(); ++i)
        j["sequences"].push_back({{"name", s.sequences[i].name}, {"held_out", i >= s.tuned}});
    j["pair"] = s.pair ? Json(s.pair->name) : Json(nullptr);
    j["axes"] = Json::array();
    for (const PrecisionAxis& a : axes) j["axes"].push_back({{"key", a.key}, {"values", a.values}});
    j["best_float"] = reference;
    j["points"] = Json::array();
    for (const Setting& p : points) {
        Json values = Json::object();
        for (const auto& [key, value] : p.values) values[key] = value;
        j["points"].push_back({{"id", p.id}, {"values", values}, {"timing", p.timing}, {"quality", p.quality}});
    }
    return j;
}

int budget_exit(const Json& report) {
    const Json& points = report["points"];
    return std::all_of(points.begin(), points.end(), setting_ran) ? kExitOk : kExitBroken;
}

}  // namespace

int quality_budget_command(const QualityBudgetOptions& o) {
    const BudgetStudy study = load_budget_study(o);
    const std::vector<PrecisionAxis> axes = parse_axes(o.axes, software_axes());
    std::vector<Setting> points = plan_settings(study, axes);
    OutputFolder out(o.out.empty() ? fs::path("traces") / "quality_budget" : fs::path(o.out),
                     {"report.json", "report.md", "results.csv", "frontier.svg"});
    std::vector<cv::Size> pair_sizes;
    const Json reference = best_float(study, pair_sizes);
    run_settings_points(study, points, pair_sizes, o, out.staging());
    Json report = study_json(study, axes, points, reference);
    analyse_quality_budget(report);
    out.publish_files({{"report.json", report.dump(2) + "\n"},
                       {"report.md", quality_budget_markdown(report)},
                       {"results.csv", quality_budget_csv(report)},
                       {"frontier.svg", quality_budget_svg(report)}});
    if (!o.quiet) std::fprintf(stderr, "%s\n", quality_budget_summary(report, out.folder() / "report.md").c_str());
    return budget_exit(report);
}

}  // namespace surfvp
