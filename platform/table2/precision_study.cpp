#include "platform/table2/precision_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <optional>

#include "models/fhg/fhg_regs.h"
#include "platform/run/progress_line.h"
#include "platform/cost/fpga_resources.h"
#include "platform/run/output_folder.h"
#include "platform/scenario/scenario.h"
#include "platform/run/resimulation.h"
#include "platform/sweep/sweep_plan.h"
#include "platform/table2/columns.h"
#include "platform/table2/precision_axis.h"
#include "platform/scenario/block_params.h"
#include "platform/workload/surf_settings.h"
#include "platform/workload/workload.h"

namespace surfvp {
namespace {
using namespace table2;
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr double kPrecisionTolerance = 0.01;  // issue: "within 0.01 of full precision" on every row

using Axis = PrecisionAxis;

// The built-in study: each width narrowed from its default toward where it breaks.
std::vector<Axis> default_axes() {
    return {{"fhg.accumulator_bits", {"22 bit", "20 bit", "18 bit"}},
            {"fhg.response_bits", {"16 bit", "14 bit", "12 bit", "10 bit"}},
            {"fhg.response_frac_bits", {"8 bit", "6 bit", "4 bit", "2 bit"}},
            {"fhg.recip_shift", {"12 bit", "8 bit", "4 bit", "2 bit"}},
            {"fhg.weight_frac_bits", {"8 bit", "4 bit", "2 bit"}},
            {"fhg.det_bits", {"24 bit", "20 bit", "16 bit"}},
            {"iig.sum_bits", {"27 bit"}},
            {"surf.haar", {"exact"}}};
}

std::string set_of(const std::string& key, const std::string& value) { return key + "=" + value; }

// A width that binds others, kept meaningful when it alone is asked for: the responses keep
// their 8 integer bits and sign (response_frac_bits = response_bits - 9), the determinant word
// its 16 (det_frac_bits = det_bits - 16), and det_frac_bits never exceeds 2 x
// response_frac_bits (the model refuses it).
std::vector<std::string> point_sets(const Config& base,
                                    const std::vector<std::pair<std::string, std::string>>& values) {
    std::vector<std::pair<std::string, std::string>> chosen = values;
    auto config = [&] {
        Config c = base;
        std::vector<std::string> sets;
        for (const auto& [key, value] : chosen) sets.push_back(set_of(key, value));
        apply_overrides(c, sets);
        return c;
    };
    auto asked = [&](const std::string& key) {
        return std::any_of(values.begin(), values.end(), [&](const auto& kv) { return kv.first == key; });
    };
    // A bound width follows unless it was asked for itself.
    auto follow = [&](const char* key, int bits) {
        if (asked(key)) return;
        const std::string value = fmt::format("{} bit", std::max(bits, 0));
        auto it = std::find_if(chosen.begin(), chosen.end(), [&](const auto& kv) { return kv.first == key; });
        if (it == chosen.end())
            chosen.push_back({key, value});
        else
            it->second = value;
    };
    auto widths = [&] { return fhg_params(config()).precision; };
    fhg::Precision w = widths();
    if (asked("fhg.response_bits"))
        follow("fhg.response_frac_bits", std::min(int(w.response_frac_bits), int(w.response_bits) - 9));
    w = widths();
    if (asked("fhg.det_bits")) follow("fhg.det_frac_bits", std::min(int(w.det_frac_bits), int(w.det_bits) - 16));
    w = widths();
    if (w.det_frac_bits > 2 * w.response_frac_bits) follow("fhg.det_frac_bits", 2 * int(w.response_frac_bits));
    std::vector<std::string> sets;
    for (const auto& [key, value] : chosen) sets.push_back(set_of(key, value));
    return sets;
}

struct PrecisionPoint {
    std::string key, value;  // the width narrowed ("" for the scenario as it is, "all" for the fewest together)
    std::vector<std::string> sets;
    Json result;
};

// In a child: the chip on the sequence (and the pair), and what its widths cost.
Json measure(const Config& seq, const std::optional<Config>& pair, const std::vector<cv::Size>& pair_sizes,
             const fs::path& scratch) {
    const Column chip = fpga_column(seq, scratch / "sequence", {});
    Json j = quality_line(chip, read_geometry(seq));
    j["chip_run_exit"] = chip.exit_code;
    if (pair) {
        const Column on_pair = fpga_column(*pair, scratch / "pair", pair_sizes);
        const Json q = quality_line(on_pair, read_geometry(*pair));
        j["pair"] = {{"repeatability", q["repeatability"]}, {"precision", q["precision"]}};
    }
    const FpgaResources fpga = fpga_resources(seq);
    j["ramb36"] = fpga.total.ramb36, j["dsp48e"] = fpga.total.dsp48e, j["luts"] = fpga.total.luts;
    const Json report = Json::parse(std::ifstream(scratch / "sequence" / "report.json"));
    const double blocks =
        double((report["image"]["width"].get<int>() + 1) / 2) * ((report["image"]["height"].get<int>() + 1) / 2);
    j["det_bytes_per_frame"] =
        blocks * fhg_regs::record_bytes(fhg_regs::det_bytes_for(fhg_params(seq).precision.det_bits));
    fs::remove_all(scratch);
    return j;
}

// Full precision: the chip's algorithm in float (chip_surf_params with the point's Haar mode),
// per Haar mode asked for.
Json full_precision(const Config& seq, const std::optional<Config>& pair, const std::string& haar) {
    Variant v{"float", "full precision: the float reference with the chip's settings", chip_surf_params(seq)};
    v.params.haar = haar == "rounded" ? surf::HaarMode::rounded : surf::HaarMode::exact;
    Json j = quality_line(cpu_column(seq, v), read_geometry(seq));
    if (pair) {
        const Json q = quality_line(cpu_column(*pair, v), read_geometry(*pair));
        j["pair"] = {{"repeatability", q["repeatability"]}, {"precision", q["precision"]}};
    }
    return j;
}

// Each row's change from full precision; the worst of them.
void compare(Json& r, const Json& reference) {
    if (!r.contains("ransac")) return;
    double worst = 1;
    Json change = Json::array();
    for (size_t i = 0; i < 4; ++i) {
        const double d = r["ransac"][i].get<double>() - reference["ransac"][i].get<double>();
        change.push_back(d), worst = std::min(worst, d);
    }
    r["change"] = change;
    r["worst_change"] = worst;
    r["within"] = worst >= -kPrecisionTolerance;
}

bool numeric(const std::string& value) { return split_quantity(value).has_value(); }
double number(const std::string& value) { return split_quantity(value)->first; }

// Per numeric axis: the fewest bits such that it and every wider value tried (and the
// scenario's own) keep every row within the tolerance; nothing when even the widest fails.
std::vector<std::pair<std::string, std::string>> fewest_bits(const std::vector<Axis>& axes,
                                                             const std::vector<PrecisionPoint>& points,
                                                             const Config& base) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const Axis& a : axes) {
        if (a.values.empty() || !numeric(a.values[0])) continue;
        std::vector<std::pair<double, bool>> tried{
            {number(base.value(a.key)), points[0].result.value("within", false)}};
        for (const PrecisionPoint& p : points)
            if (p.key == a.key) tried.push_back({number(p.value), p.result.value("within", false)});
        std::sort(tried.rbegin(), tried.rend());
        std::optional<double> fewest;
        for (const auto& [v, ok] : tried) {
            if (!ok) break;
            fewest = v;
        }
        if (fewest) out.push_back({a.key, fmt::format("{:g} bit", *fewest)});
    }
    return out;
}

std::string cell(const Json& r, const char* key, const char* format) {
    return r.contains(key) ? fmt::format(fmt::runtime(format), r[key].get<double>()) : "-";
}

std::string precision_markdown(const Json& report) {
    std::string md = fmt::format(
        "# Precision study: {}\n\nThe chip (direct mode) on `{}`{} with one width narrowed at a time. "
        "Rows: distinguishability on consecutive frames, RANSAC F (limited search Y/N, Laplacian Y/N); "
        "change from full precision (the same algorithm in float) in brackets. A point is within when "
        "no row lost more than {:g}.\n\n",
        report["scenario"].get<std::string>(), report["scenario"].get<std::string>(),
        report["pair"].is_null() ? "" : fmt::format(" and `{}`", report["pair"].get<std::string>()),
        kPrecisionTolerance);
    const double error = report["standard_error"].get<double>();
    const std::string noise = error > 0 ? fmt::format("and the tolerance of {:g} is {:.1f} of them",
                                                      kPrecisionTolerance, kPrecisionTolerance / error)
                                        : std::string("and here the pairs do not spread at all");
    md += fmt::format(
        "Keypoints per frame: {}. Over {} pairs the rows' standard error is about {:.3f}: a change smaller than that "
        "is noise, {}.\n\n",
        report["threshold_control"] == "track" ? "each point holds its count near the target (surf.threshold_control = "
                                                 "track), since narrower arithmetic scales the determinants"
                                               : "the calibrated threshold is held (surf.threshold_control = hold)",
        report["pairs"].get<size_t>(), error, noise);
    md +=
        "| width | value | keypoints per frame | Y Y | Y N | N Y | N N | within | repeatability | precision | RAMB36 | "
        "DSP48E | LUTs | "
        "det bytes/frame |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    auto line = [&](const std::string& key, const std::string& value, const Json& r) {
        if (r.contains("error"))
            return fmt::format("| {} | {} | {} ||||||||||||\n", key, value, r["error"].get<std::string>());
        std::string row = fmt::format("| {} | {} | {:.1f} |", key, value, r["keypoints_per_frame"].get<double>());
        for (size_t i = 0; i < 4; ++i)
            row += r.contains("change") ? fmt::format(" {:.3f} ({:+.3f}) |", r["ransac"][i].get<double>(),
                                                      r["change"][i].get<double>() + 0.0)
                                        : fmt::format(" {:.3f} |", r["ransac"][i].get<double>());
        row += r.contains("within") ? (r["within"].get<bool>() ? " yes |" : " **no** |") : " |";
        const Json pair = r.value("pair", Json::object());
        row += fmt::format(" {} | {} | {} | {} | {} | {} |\n", cell(pair, "repeatability", "{:.3f}"),
                           cell(pair, "precision", "{:.3f}"), cell(r, "ramb36", "{:g}"), cell(r, "dsp48e", "{:g}"),
                           cell(r, "luts", "{:.0f}"), cell(r, "det_bytes_per_frame", "{:.0f}"));
        return row;
    };
    for (const auto& [haar, r] : report["full_precision"].items())
        md += line("full precision", "float, Haar " + haar, r);
    for (const Json& p : report["points"]) md += line(p["key"], p["value"], p["result"]);
    md += "\n## Fewest bits\n\n| width | fewest bits within " + fmt::format("{:g}", kPrecisionTolerance) +
          " | the scenario's |\n|---|---|---|\n";
    for (const Json& f : report["fewest_bits"])
        md += fmt::format("| {} | {} | {} |\n", f["key"].get<std::string>(), f["fewest"].get<std::string>(),
                          f["scenario"].get<std::string>());
    const Json& all = report["all_fewest_together"];
    if (!all.is_null())
        md += fmt::format("\nAll of them together (`{}`): {}.\n",
                          all["sets"].get<std::vector<std::string>>().size()
                              ? fmt::format("{}", fmt::join(all["sets"].get<std::vector<std::string>>(), "`, `"))
                              : "",
                          all["result"].value("within", false)
                              ? "every row within the tolerance"
                              : "a row falls outside the tolerance: the widths interact");
    md +=
        "\nNarrowing `fhg.response_bits` keeps the responses' 8 integer bits and sign (response_frac_bits = "
        "response_bits - 9), "
        "`fhg.det_bits` the determinant word's 16 (det_frac_bits = det_bits - 16), and det_frac_bits never exceeds 2 x "
        "response_frac_bits.\n";
    return md;
}

// precision.svg: per width, the worst row's change from full precision against its bits.
std::string plot(const Json& report) {
    std::vector<std::string> keys;
    for (const Json& p : report["points"])
        if (p["key"] != "" && p["key"] != "all" && p["result"].contains("worst_change") && numeric(p["value"]) &&
            std::find(keys.begin(), keys.end(), p["key"]) == keys.end())
            keys.push_back(p["key"]);
    const double W = 300, H = 200, L = 46, B = 30, T = 24;
    const int cols = 2, rows = int((keys.size() + 1) / 2);
    std::string svg = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" "
        "font-size=\"11\"><rect width=\"100%\" height=\"100%\" fill=\"white\"/>",
        W * cols, H * rows + 24);
    svg += fmt::format(
        "<text x=\"8\" y=\"16\" font-size=\"13\">worst row's change from full precision against each width "
        "(dashed: -{:g})</text>",
        kPrecisionTolerance);
    double y0 = -0.05, y1 = 0.03;  // widened to every point's change
    for (const Json& p : report["points"])
        if (p["result"].contains("worst_change") && p["key"] != "all")
            y0 = std::min(y0, p["result"]["worst_change"].get<double>() - 0.01),
            y1 = std::max(y1, p["result"]["worst_change"].get<double>() + 0.01);
    for (size_t k = 0; k < keys.size(); ++k) {
        const double ox = double(k % 2) * W, oy = 24 + double(k / 2) * H;
        std::vector<std::pair<double, double>> pts{{number(report["scenario_values"][keys[k]].get<std::string>()),
                                                    report["points"][0]["result"].value("worst_change", 0.0)}};
        for (const Json& p : report["points"])
            if (p["key"] == keys[k] && p["result"].contains("worst_change"))
                pts.push_back({number(p["value"]), p["result"]["worst_change"]});
        std::sort(pts.begin(), pts.end());
        const double x0 = pts.front().first, x1 = std::max(pts.back().first, x0 + 1);
        auto px = [&](double x) { return ox + L + (x - x0) / (x1 - x0) * (W - L - 12); };
        auto py = [&](double y) { return oy + T + (y1 - std::clamp(y, y0, y1)) / (y1 - y0) * (H - T - B); };
        svg += fmt::format("<text x=\"{}\" y=\"{}\">{}</text>", ox + L, oy + 14, keys[k]);
        svg += fmt::format(
            "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#c00\" stroke-dasharray=\"5 3\"/>",
            ox + L, py(-kPrecisionTolerance), ox + W - 12);
        svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">bit</text>", ox + W - 12, oy + 14);
        for (double y : {y0, -kPrecisionTolerance, 0.0, y1})
            svg +=
                fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{:+.2f}</text>", ox + L - 4, py(y) + 4, y);
        std::string line;
        for (const auto& [x, y] : pts) {
            line += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
            svg += fmt::format(
                "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"#1b3a5c\"><title>{:g} bit: {:+.3f}</title></circle>"
                "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{:g}</text>",
                px(x), py(y), x, y, px(x), oy + H - B + 14, x);
        }
        svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"#1b3a5c\"/>", line);
    }
    return svg + "</svg>";
}

std::string csv(const Json& report) {
    std::string out =
        "key,value,keypoints_per_frame,yy,yn,ny,nn,worst_change,within,repeatability,precision,ramb36,dsp48e,luts,det_"
        "bytes_per_frame,error\n";
    for (const Json& p : report["points"]) {
        const Json& r = p["result"];
        auto num = [&](const Json& j, const char* k) {
            return j.contains(k) ? fmt::format("{:.6g}", j[k].get<double>()) : std::string();
        };
        const Json pair = r.value("pair", Json::object());
        out += fmt::format("{},{},{},", p["key"].get<std::string>(), p["value"].get<std::string>(),
                           num(r, "keypoints_per_frame"));
        for (size_t i = 0; i < 4; ++i)
            out += r.contains("ransac") ? fmt::format("{:.6g},", r["ransac"][i].get<double>()) : ",";
        out += fmt::format("{},{},{},{},{},{},{},{},\"{}\"\n", num(r, "worst_change"),
                           r.contains("within") ? (r["within"].get<bool>() ? "true" : "false") : "",
                           num(pair, "repeatability"), num(pair, "precision"), num(r, "ramb36"), num(r, "dsp48e"),
                           num(r, "luts"), num(r, "det_bytes_per_frame"), r.value("error", ""));
    }
    return out;
}

// The sequence and the pair (each point's widths apply to both), loaded and checked.
struct Study {
    Config seq;
    std::optional<Config> pair;
    std::vector<const Config*> both() const { return pair ? std::vector{&seq, &*pair} : std::vector{&seq}; }
};

Study load_study(const PrecisionOptions& o) {
    Study s{load_scenario(resolve_scenario(o.scenario), o.sets), std::nullopt};
    if (!o.pair.empty())
        s.pair = load_scenario(resolve_scenario(o.pair), {});  // it takes each point's widths, not --set
    // Narrower arithmetic scales the determinants, so a held threshold would change the keypoint
    // count and with it distinguishability: each point holds its count, unless told otherwise.
    for (Config* c : std::vector<Config*>{&s.seq, s.pair ? &*s.pair : nullptr})
        if (c && c->origin("surf.threshold_control") == "default" && c->count("surf.target_keypoints") > 0)
            apply_overrides(*c, {"surf.threshold_control=track"});
    for (const Config* c : s.both()) {
        if (c->choice("run.workload") != "surf")
            throw ConfigError(fmt::format("{}: the precision study needs SURF scenarios (run.workload: surf)",
                                          c->where("run.workload")));
        check_scenario(*c);
        if (!c->faults.empty())  // the study runs the chip without time, where no fault can strike
            throw ConfigError(
                fmt::format("{}: faults: the precision study runs the chip without time; give a scenario without "
                            "faults",
                            c->faults.front().origin));
    }
    if (s.pair && s.pair->text("eval.homography").empty())
        throw ConfigError(
            fmt::format("--pair {}: a pair under a homography (eval.homography) gives repeatability and precision; "
                        "it has none",
                        o.pair));
    return s;
}

// The scenario as it is, then each value of each axis alone. Each point's scenario, and the
// pair under its widths, is checked as `validate` would (a width the model refuses): refused
// now, not after the reference ran.
std::vector<PrecisionPoint> plan_points(const Study& s, const std::vector<Axis>& axes) {
    std::vector<PrecisionPoint> points{{"", "as the scenario", {}, {}}};
    for (const Axis& a : axes)
        for (const std::string& v : a.values) try {
                points.push_back({a.key, v, point_sets(s.seq, {{a.key, v}}), {}});
                for (const Config* c : s.both()) {
                    Config at = *c;
                    apply_overrides(at, points.back().sets);
                    check_scenario(at);
                }
            } catch (const ConfigError& e) {
                throw ConfigError(fmt::format("--axis {}={}: {}", a.key, v, e.what()));
            }
    return points;
}

// Full precision under each Haar mode the points use: what each point is compared with.
Json references(const Study& s, const std::vector<PrecisionPoint>& points) {
    std::vector<std::string> haars{surf::haar_name(surf_settings(s.seq).haar)};
    for (const PrecisionPoint& p : points)
        if (p.key == "surf.haar" && std::find(haars.begin(), haars.end(), p.value) == haars.end())
            haars.push_back(p.value);
    Json reference = Json::object();
    for (const std::string& h : haars) reference[h] = full_precision(s.seq, s.pair, h);
    return reference;
}

// Runs every point in children (and, once they are in, the fewest bits of each axis
// together), each compared with its reference; returns the fewest bits.
std::vector<std::pair<std::string, std::string>> run_points(const Study& s, const std::vector<Axis>& axes,
                                                            std::vector<PrecisionPoint>& points, Json& reference,
                                                            const PrecisionOptions& o, const fs::path& staging) {
    const std::vector<cv::Size> pair_sizes =
        s.pair ? cpu_column(*s.pair, variants(*s.pair)[0]).sizes : std::vector<cv::Size>{};
    for (const Config* c : s.both()) Resimulation::prepare(*c);
    Resimulation engine(o.jobs, staging / ".points");
    ProgressLine progress(o.quiet, "precision", 1.0, 0.5, 10.0);
    auto submit = [&](size_t i) {
        Config c = s.seq;
        apply_overrides(c, points[i].sets);
        std::optional<Config> p = s.pair;
        if (p) apply_overrides(*p, points[i].sets);
        const fs::path scratch = staging / ".points" / fmt::format("point{}", i);
        engine.submit_work(
            c, [&points, i](const Json& result) { points[i].result = result; },
            [p, pair_sizes, scratch](const Config& config) { return measure(config, p, pair_sizes, scratch); });
    };
    for (size_t i = 0; i < points.size(); ++i) submit(i);
    const size_t total = points.size() + (axes.empty() ? 0 : 1);  // and the fewest bits together
    auto show = [&](size_t done, size_t) { progress.steps(done, total, "points"); };
    engine.run(show);
    const std::string haar = surf::haar_name(surf_settings(s.seq).haar);
    for (PrecisionPoint& p : points) compare(p.result, reference[p.key == "surf.haar" ? p.value : haar]);
    const auto fewest = fewest_bits(axes, points, s.seq);
    if (!fewest.empty()) {  // all of them at once
        points.push_back({"all", "the fewest bits together", point_sets(s.seq, fewest), {}});
        submit(points.size() - 1);
        engine.run(show);
        compare(points.back().result, reference[haar]);
    }
    return fewest;
}

Json study_report(const Study& s, const std::vector<Axis>& axes, const std::vector<PrecisionPoint>& points,
                  const Json& reference, const std::vector<std::pair<std::string, std::string>>& fewest) {
    const Config& seq = s.seq;
    Json report;
    report["scenario"] = seq.name;
    report["pair"] = s.pair ? Json(s.pair->name) : Json(nullptr);
    report["tolerance"] = kPrecisionTolerance;
    report["threshold_control"] = surf_settings(seq).track ? "track" : "hold";
    {  // how far apart two points must be to differ: the rows' standard error over the pairs
        const Json& full = reference[surf::haar_name(surf_settings(seq).haar)];
        double spread = 0;
        for (const Json& v : full["ransac_spread"]) spread = std::max(spread, v.get<double>());
        report["standard_error"] =
            full["pairs"].get<size_t>() ? spread / std::sqrt(double(full["pairs"].get<size_t>())) : 0.0;
        report["pairs"] = full["pairs"];
    }
    report["full_precision"] = reference;
    report["scenario_values"] = Json::object();
    for (const Axis& a : axes) report["scenario_values"][a.key] = seq.value(a.key);
    report["points"] = Json::array();
    for (const PrecisionPoint& p : points)
        report["points"].push_back({{"key", p.key}, {"value", p.value}, {"sets", p.sets}, {"result", p.result}});
    report["fewest_bits"] = Json::array();
    for (const auto& [key, value] : fewest)
        report["fewest_bits"].push_back(Json{{"key", key}, {"fewest", value}, {"scenario", seq.value(key)}});
    report["all_fewest_together"] =
        fewest.empty() ? Json(nullptr) : Json{{"sets", points.back().sets}, {"result", points.back().result}};
    return report;
}

// The study's exit code: 6 when a point could not run or its chip run broke (its row is not a
// measurement of the widths), else 1 when a chip run missed a goal (a keypoint target), else 0.
int study_exit(const std::vector<PrecisionPoint>& points) {
    int code = kExitOk;
    for (const PrecisionPoint& p : points) {
        const int exit = p.result.contains("error") ? kExitBroken : p.result.value("chip_run_exit", int(kExitOk));
        if (exit == kExitBroken) return kExitBroken;
        if (exit != kExitOk) code = kExitFailed;
    }
    return code;
}

}  // namespace

int precision_command(const PrecisionOptions& o) {
    const Study study = load_study(o);
    const std::vector<Axis> axes = parse_axes(o.axes, default_axes());
    std::vector<PrecisionPoint> points = plan_points(study, axes);
    OutputFolder out(o.out.empty() ? fs::path("traces") / ("precision_" + study.seq.name) : fs::path(o.out),
                     {"report.json", "report.md", "results.csv", "precision.svg"});
    Json reference = references(study, points);
    const auto fewest = run_points(study, axes, points, reference, o, out.staging());
    const Json report = study_report(study, axes, points, reference, fewest);
    out.publish_files({{"report.json", report.dump(2) + "\n"},
                       {"report.md", precision_markdown(report)},
                       {"results.csv", csv(report)},
                       {"precision.svg", plot(report)}});
    if (!o.quiet)
        std::fprintf(stderr, "surfvp: precision: %zu points; report in %s\n", points.size(),
                     (out.folder() / "report.md").c_str());
    return study_exit(points);
}

}  // namespace surfvp
