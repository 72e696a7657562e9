#include "platform/table2/quality_budget_report.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <vector>

#include "platform/report/chart_ticks.h"
#include "platform/run/run.h"

namespace surfvp {
namespace {
using Json = nlohmann::ordered_json;

constexpr const char* kRows[4] = {"Y Y", "Y N", "N Y", "N N"};

// The mean of a quality line's four rows, when every cell was measured.
std::optional<double> row_mean(const Json& line) {
    if (!line.contains("ransac")) return std::nullopt;
    double sum = 0;
    for (size_t r = 0; r < 4; ++r) {
        if (!line["ransac_measured"][r].get<bool>()) return std::nullopt;
        sum += line["ransac"][r].get<double>();
    }
    return sum / 4;
}

// Distinguishability over the sequences chosen on (not the held-out ones).
Json distinguishability(const Json& report, const Json& sequences) {
    double sum = 0;
    size_t n = 0;
    for (size_t i = 0; i < sequences.size(); ++i) {
        if (report["sequences"][i]["held_out"].get<bool>()) continue;
        const auto m = row_mean(sequences[i]);
        if (!m) return nullptr;
        sum += *m, ++n;
    }
    return n ? Json(sum / double(n)) : Json(nullptr);
}

Json pair_precision(const Json& quality) {
    return quality.contains("pair") && quality["pair"].value("precision", Json(nullptr)).is_number()
               ? quality["pair"]["precision"]
               : Json(nullptr);
}

double fps_step(double fps) { return std::round(fps / kFrontFpsResolution) * kFrontFpsResolution; }

// Marks `flag` on the points no other point beats in both frames/s and `metric`.
void mark_front(Json& points, const char* metric, const char* flag) {
    for (Json& p : points) {
        p[flag] = false;
        if (!p[metric].is_number()) continue;
        const double f = fps_step(p["timing"]["fps"].get<double>()), m = p[metric].get<double>();
        bool beaten = false;
        for (const Json& q : points) {
            if (!q[metric].is_number()) continue;
            const double qf = fps_step(q["timing"]["fps"].get<double>()), qm = q[metric].get<double>();
            beaten = beaten || (qf >= f && qm >= m && (qf > f || qm > m));
        }
        p[flag] = !beaten;
    }
}

// Each sequence's four rows of a point against the best float's: the point's and the difference.
Json gaps(const Json& report, const Json& point) {
    Json out = Json::array();
    for (size_t i = 0; i < report["sequences"].size(); ++i) {
        const Json& line = point["quality"]["sequences"][i];
        const Json& ref = report["best_float"]["sequences"][i];
        Json rows = Json::array();
        for (size_t r = 0; r < 4; ++r) {
            const bool measured = line["ransac_measured"][r].get<bool>() && ref["ransac_measured"][r].get<bool>();
            rows.push_back({{"row", kRows[r]},
                            {"float", ref["ransac"][r]},
                            {"chip", line["ransac"][r]},
                            {"gap", measured ? Json(line["ransac"][r].get<double>() - ref["ransac"][r].get<double>())
                                             : Json(nullptr)}});
        }
        out.push_back({{"sequence", report["sequences"][i]["name"]},
                       {"held_out", report["sequences"][i]["held_out"]},
                       {"rows", rows}});
    }
    return out;
}

std::string num(const Json& j, const char* format = "{:.3f}") {
    return j.is_number() ? fmt::format(fmt::runtime(format), j.get<double>() + 0.0) : std::string("-");
}

std::string rows_text(const Json& line) {
    if (!line.contains("ransac")) return "-";
    std::vector<std::string> cells;
    for (size_t r = 0; r < 4; ++r)
        cells.push_back(line["ransac_measured"][r].get<bool>() ? num(line["ransac"][r]) : "not measured");
    return fmt::format("{}", fmt::join(cells, " / "));
}

std::string setting_name(const Json& report, size_t i) {
    return i == 0 ? "the paper's software (the scenarios as they are)" : report["points"][i]["id"].get<std::string>();
}

std::string settings_table(const Json& r) {
    std::string md =
        "| setting | CPU µs per keypoint | CPU alone, frames/s | frames/s | limited by | keypoints per frame |";
    std::string rule = "|---|---|---|---|---|---|";
    for (const Json& s : r["sequences"])
        md += fmt::format(" {}{} |", s["name"].get<std::string>(), s["held_out"].get<bool>() ? " (held out)" : ""),
            rule += "---|";
    if (!r["pair"].is_null()) md += " repeatability | precision |", rule += "---|---|";
    md += " distinguishability | affordable | front |\n" + rule + "---|---|---|\n";
    for (size_t i = 0; i < r["points"].size(); ++i) {
        const Json& p = r["points"][i];
        const Json& t = p["timing"];
        const Json& q = p["quality"];
        if (!setting_ran(p)) {
            const std::string why = t.value("error", q.value("error", std::string("the chip run broke")));
            md += fmt::format("| {} | could not run: {} |\n", setting_name(r, i), why);
            continue;
        }
        md += fmt::format("| {} | {} | {} | {} | {} | {} |", setting_name(r, i), num(t["us_per_keypoint"], "{:.0f}"),
                          num(t["cpu_fps"], "{:.2f}"), num(t["fps"], "{:.2f}"), t["limit"].get<std::string>(),
                          num(t["keypoints_per_frame"], "{:.1f}"));
        for (const Json& line : q["sequences"]) md += " " + rows_text(line) + " |";
        if (!r["pair"].is_null())
            md += fmt::format(" {} | {} |", num(q["pair"]["repeatability"]), num(q["pair"]["precision"]));
        md += fmt::format(" {} | {} | {} |\n", num(p["distinguishability"]), p["affordable"].get<bool>() ? "yes" : "no",
                          p["front"].get<bool>() ? "**yes**" : "");
    }
    return md;
}

// Every row of every sequence: the best float, then each chip setting and its difference from it.
std::string gap_table(const Json& r) {
    std::vector<std::pair<const char*, const char*>> columns{{"paper_software", "the paper's software"},
                                                             {"best_affordable", "best affordable"}};
    if (r["gaps"].contains("best_affordable_oriented"))
        columns.push_back({"best_affordable_oriented", "best affordable with orientation"});
    std::string md = "| sequence | row | best float |", rule = "|---|---|---|";
    for (const auto& [key, title] : columns) md += fmt::format(" {0} | {0} − float |", title), rule += "---|---|";
    md += "\n" + rule + "\n";
    const Json& paper = r["gaps"]["paper_software"];
    for (size_t i = 0; i < paper.size(); ++i)
        for (size_t row = 0; row < 4; ++row) {
            md += fmt::format("| {}{} | {} | {} |", paper[i]["sequence"].get<std::string>(),
                              paper[i]["held_out"].get<bool>() ? " (held out)" : "", kRows[row],
                              num(paper[i]["rows"][row]["float"]));
            for (const auto& [key, title] : columns) {
                const Json& cell = r["gaps"][key][i]["rows"][row];
                md += fmt::format(" {} | {} |", num(cell["chip"]), num(cell["gap"], "{:+.3f}"));
            }
            md += "\n";
        }
    return md;
}

std::string front_table(const Json& r, const char* metric, const char* flag, const std::string& title) {
    std::vector<size_t> on;
    for (size_t i = 0; i < r["points"].size(); ++i)
        if (r["points"][i].value(flag, false)) on.push_back(i);
    std::sort(on.begin(), on.end(), [&](size_t a, size_t b) {
        return r["points"][a]["timing"]["fps"].get<double>() > r["points"][b]["timing"]["fps"].get<double>();
    });
    std::string md = fmt::format("| frames/s | {} | CPU alone, frames/s | setting |\n|---|---|---|---|\n", title);
    for (size_t i : on) {
        const Json& p = r["points"][i];
        md += fmt::format("| {} | {} | {} | {} |\n", num(p["timing"]["fps"], "{:.2f}"), num(p[metric]),
                          num(p["timing"]["cpu_fps"], "{:.2f}"), setting_name(r, i));
    }
    return md;
}

// The most distinguishable of the points `take` accepts (then the most precise, then the fastest).
template <typename Take>
std::optional<size_t> best_of(const Json& points, Take take) {
    auto key = [&](size_t i) {
        const Json& p = points[i];
        return std::make_tuple(p["distinguishability"].get<double>(),
                               p["precision"].is_number() ? p["precision"].get<double>() : 0.0,
                               p["timing"]["fps"].get<double>());
    };
    std::optional<size_t> best;
    for (size_t i = 0; i < points.size(); ++i)
        if (take(points[i]) && (!best || key(i) > key(*best))) best = i;
    return best;
}

}  // namespace

bool setting_ran(const Json& p) {
    for (const char* part : {"timing", "quality"})
        if (!p[part].is_object() || p[part].contains("error") || p[part].value("exit", int(kExitOk)) == kExitBroken)
            return false;
    return true;
}

void analyse_quality_budget(Json& r) {
    const double budget = r["budget_fps"].get<double>();
    for (Json& p : r["points"]) {
        const bool ok = setting_ran(p);
        p["distinguishability"] = ok ? distinguishability(r, p["quality"]["sequences"]) : Json(nullptr);
        p["precision"] = ok ? pair_precision(p["quality"]) : Json(nullptr);
        p["affordable"] = ok && p["timing"]["cpu_fps"].get<double>() >= budget;
        p["meets_budget"] = ok && p["timing"]["fps"].get<double>() >= budget;
    }
    mark_front(r["points"], "distinguishability", "front");
    mark_front(r["points"], "precision", "precision_front");
    r["best_float_distinguishability"] = distinguishability(r, r["best_float"]["sequences"]);
    r["best_float_precision"] = pair_precision(r["best_float"]);
    // A setting that scores better on the sequences by giving up what they do not test (upright
    // keypoints on frames that never rotate) shows it on the pair: the best may not lose precision.
    const Json& paper = r["points"][0]["precision"];
    auto candidate = [&](const Json& p) {
        return p["affordable"].get<bool>() && p["distinguishability"].is_number() &&
               (!paper.is_number() || (p["precision"].is_number() && p["precision"] >= paper));
    };
    const auto best = best_of(r["points"], candidate);
    r["best_affordable"] = best ? Json(*best) : Json(nullptr);
    // An upright best gives up rotation invariance: the best that keeps the orientation beside it.
    const auto upright = [](const Json& p) { return p["values"].value("surf.upright", "") == "on"; };
    const auto oriented = best && upright(r["points"][*best])
                              ? best_of(r["points"], [&](const Json& p) { return candidate(p) && !upright(p); })
                              : std::nullopt;
    r["best_affordable_oriented"] = oriented ? Json(*oriented) : Json(nullptr);
    r["gaps"] = Json::object();
    if (!setting_ran(r["points"][0])) return;
    r["gaps"]["paper_software"] = gaps(r, r["points"][0]);
    if (best) r["gaps"]["best_affordable"] = gaps(r, r["points"][*best]);
    if (oriented) r["gaps"]["best_affordable_oriented"] = gaps(r, r["points"][*oriented]);
}

std::string quality_budget_markdown(const Json& r) {
    std::string md = fmt::format(
        "# Quality at the budget: {} at {:g} frames/s\n\n"
        "Each setting of the CPU stage's software, priced on `{}` (a timed run: the CPU's time per keypoint from the "
        "calibrated PPC440 model, the frame rate the CPU alone would sustain, the chip's frame rate and what limits "
        "it) and scored by the chip (direct mode) on Table II sequences: distinguishability on consecutive frames, "
        "RANSAC F, the four rows (limited search, Laplacian: Y Y / Y N / N Y / N N){}. A setting is **affordable** "
        "when the CPU alone sustains the budget: it then costs the chip no frame rate the budget needs. The best "
        "affordable setting is the most distinguishable one that keeps the pair's precision at least the paper's "
        "software's (a setting may score on sequences that never rotate by giving up rotation invariance). The "
        "distinguishability column is the mean of the four rows over the sequences not held out; held-out sequences "
        "are scored, never chosen on.\n\n",
        r["budget_scenario"].get<std::string>(), r["budget_fps"].get<double>(), r["budget_scenario"].get<std::string>(),
        r["pair"].is_null() ? ""
                            : fmt::format("; repeatability and precision (correct / candidates) on the pair `{}`",
                                          r["pair"].get<std::string>()));
    const Json& best = r["best_affordable"];
    if (best.is_null())
        md += "**No setting is affordable**: the CPU alone misses the budget with each of them.\n\n";
    else {
        const Json& p = r["points"][best.get<size_t>()];
        const Json& paper = r["points"][0];
        md += fmt::format(
            "**The best affordable setting: {}.** Distinguishability {} (the paper's software {}, the best float SURF "
            "{}){}; {} µs of CPU a keypoint, the CPU alone {} frames/s, the chip {} frames/s (limited by {}).\n\n",
            setting_name(r, best.get<size_t>()), num(p["distinguishability"]), num(paper["distinguishability"]),
            num(r["best_float_distinguishability"]),
            r["pair"].is_null()
                ? ""
                : fmt::format("; precision on {} {} (paper's {}, float {})", r["pair"].get<std::string>(),
                              num(p["precision"]), num(paper["precision"]), num(r["best_float_precision"])),
            num(p["timing"]["us_per_keypoint"], "{:.0f}"), num(p["timing"]["cpu_fps"], "{:.2f}"),
            num(p["timing"]["fps"], "{:.2f}"), p["timing"]["limit"].get<std::string>());
        const Json& oriented = r["best_affordable_oriented"];
        if (!oriented.is_null()) {
            const Json& o = r["points"][oriented.get<size_t>()];
            md += fmt::format(
                "Its keypoints are upright (`surf.upright=on`): they have no orientation, so they match only while "
                "the camera does not roll; the sequences here hardly rotate. The best affordable setting that keeps "
                "the orientation: **{}**, distinguishability {}{}, {} µs of CPU a keypoint, the CPU alone {} "
                "frames/s.\n\n",
                setting_name(r, oriented.get<size_t>()), num(o["distinguishability"]),
                r["pair"].is_null() ? "" : ", precision " + num(o["precision"]),
                num(o["timing"]["us_per_keypoint"], "{:.0f}"), num(o["timing"]["cpu_fps"], "{:.2f}"));
        }
        if (r["gaps"].contains("best_affordable"))
            md += "Against the best float SURF (sw/surf at its defaults), every row:\n\n" + gap_table(r) + "\n";
    }
    md +=
        "## Every setting\n\nEach sequence's cell: its four rows. \"front\": no other setting has both a higher "
        "frame rate (to " +
        fmt::format("{:g}", kFrontFpsResolution) + " frames/s) and a higher distinguishability.\n\n" +
        settings_table(r) + "\n## The fronts\n\nDistinguishability against frames/s:\n\n" +
        front_table(r, "distinguishability", "front", "distinguishability");
    if (!r["pair"].is_null())
        md += "\nPrecision on " + r["pair"].get<std::string>() + " against frames/s:\n\n" +
              front_table(r, "precision", "precision_front", "precision");
    return md + "\n![quality against frames/s](frontier.svg)\n";
}

std::string quality_budget_csv(const Json& r) {
    std::string out = "setting";
    for (const Json& a : r["axes"]) out += "," + a["key"].get<std::string>();
    out += ",fps,cpu_fps,us_per_keypoint,keypoints_per_frame,limit";
    for (const Json& s : r["sequences"])
        for (const char* row : {"yy", "yn", "ny", "nn"})
            out += fmt::format(",{}_{}", s["name"].get<std::string>(), row);
    out += ",repeatability,precision,distinguishability,affordable,front,precision_front,error\n";
    for (size_t i = 0; i < r["points"].size(); ++i) {
        const Json& p = r["points"][i];
        auto n = [](const Json& j) { return j.is_number() ? fmt::format("{:.6g}", j.get<double>()) : std::string(); };
        out += fmt::format("\"{}\"", p["id"].get<std::string>());
        for (const Json& a : r["axes"]) out += "," + p["values"].value(a["key"].get<std::string>(), std::string());
        const Json t = p["timing"].is_object() ? p["timing"] : Json::object();
        const Json q = p["quality"].is_object() ? p["quality"] : Json::object();
        out += fmt::format(",{},{},{},{},{}", n(t.value("fps", Json())), n(t.value("cpu_fps", Json())),
                           n(t.value("us_per_keypoint", Json())), n(t.value("keypoints_per_frame", Json())),
                           t.value("limit", std::string()));
        for (size_t s = 0; s < r["sequences"].size(); ++s)
            for (size_t row = 0; row < 4; ++row)
                out += "," + (q.contains("sequences") ? n(q["sequences"][s]["ransac"][row]) : std::string());
        const Json pair = q.value("pair", Json::object());
        out += fmt::format(",{},{},{},{},{},{},\"{}\"\n", n(pair.value("repeatability", Json())),
                           n(pair.value("precision", Json())), n(p["distinguishability"]),
                           p["affordable"].get<bool>() ? "true" : "false", p["front"].get<bool>() ? "true" : "false",
                           p["precision_front"].get<bool>() ? "true" : "false",
                           t.value("error", q.value("error", std::string())));
    }
    return out;
}

std::string quality_budget_svg(const Json& r) {
    const bool pair = !r["pair"].is_null();
    const double W = 460, H = 320, L = 56, B = 40, T = 30, Rm = 16;
    const int panels = pair ? 2 : 1;
    std::string svg = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" "
        "font-size=\"11\"><rect width=\"100%\" height=\"100%\" fill=\"white\"/>"
        "<text x=\"8\" y=\"16\" font-size=\"13\">Quality against frames/s on {}, each software setting</text>"
        "<text x=\"8\" y=\"32\">filled: affordable (the CPU alone holds {:g} frames/s); line: the front; red ring: "
        "the best affordable; dashed: the budget (red) and the best float SURF (green)</text>",
        W * panels, H + 40, r["budget_scenario"].get<std::string>(), r["budget_fps"].get<double>());
    double f0 = r["budget_fps"].get<double>(), f1 = f0;
    for (const Json& p : r["points"])
        if (p["timing"].is_object() && p["timing"].contains("fps"))
            f0 = std::min(f0, p["timing"]["fps"].get<double>()), f1 = std::max(f1, p["timing"]["fps"].get<double>());
    const Ticks fx = round_ticks(f0, f1);
    const std::vector<std::tuple<const char*, const char*, const char*, const char*>> metrics{
        {"distinguishability", "front", "best_float_distinguishability", "distinguishability (mean of the rows)"},
        {"precision", "precision_front", "best_float_precision", "precision on the pair"}};
    for (int k = 0; k < panels; ++k) {
        const auto& [metric, flag, reference, title] = metrics[size_t(k)];
        double m0 = 1, m1 = 0;
        for (const Json& p : r["points"])
            if (p[metric].is_number())
                m0 = std::min(m0, p[metric].get<double>()), m1 = std::max(m1, p[metric].get<double>());
        if (r[reference].is_number())
            m0 = std::min(m0, r[reference].get<double>()), m1 = std::max(m1, r[reference].get<double>());
        if (m1 < m0) m0 = 0, m1 = 1;
        const Ticks my = round_ticks(m0, m1);
        const double ox = W * k, oy = 40;
        auto px = [&](double f) { return ox + L + (f - fx.lo()) / (fx.hi() - fx.lo()) * (W - L - Rm); };
        auto py = [&](double m) { return oy + T + (my.hi() - m) / (my.hi() - my.lo()) * (H - T - B); };
        svg += fmt::format("<text x=\"{}\" y=\"{}\">{}</text>", ox + L, oy + 16, title);
        for (double t : fx.at)
            svg += fmt::format(
                "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#eee\"/>"
                "<text x=\"{0:.1f}\" y=\"{3:.1f}\" text-anchor=\"middle\">{4}</text>",
                px(t), py(my.hi()), py(my.lo()), py(my.lo()) + 14, tick_label(t, fx.step));
        for (double t : my.at)
            svg += fmt::format(
                "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#eee\"/>"
                "<text x=\"{3:.1f}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>",
                px(fx.lo()), py(t), px(fx.hi()), px(fx.lo()) - 4, py(t) + 4, tick_label(t, my.step));
        svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">frames/s</text>",
                           (px(fx.lo()) + px(fx.hi())) / 2, py(my.lo()) + 30);
        svg += fmt::format(
            "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#c00\" "
            "stroke-dasharray=\"5 3\"><title>budget {3:g} frames/s</title></line>",
            px(r["budget_fps"].get<double>()), py(my.hi()), py(my.lo()), r["budget_fps"].get<double>());
        if (r[reference].is_number())
            svg += fmt::format(
                "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#2a7\" "
                "stroke-dasharray=\"5 3\"><title>best float SURF {3:.3f}</title></line>",
                px(fx.lo()), py(r[reference].get<double>()), px(fx.hi()), r[reference].get<double>());
        std::vector<std::pair<double, double>> front;
        for (size_t i = 0; i < r["points"].size(); ++i) {
            const Json& p = r["points"][i];
            if (!p[metric].is_number()) continue;
            const double x = px(p["timing"]["fps"].get<double>()), y = py(p[metric].get<double>());
            if (p[flag].get<bool>()) front.push_back({x, y});
            svg += fmt::format(
                "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\" stroke=\"#1b3a5c\"><title>{}: "
                "{:.3f}, {:.2f} frames/s</title></circle>",
                x, y, p["affordable"].get<bool>() ? "#1b3a5c" : "white", setting_name(r, i), p[metric].get<double>(),
                p["timing"]["fps"].get<double>());
            if (r["best_affordable"] == i)
                svg += fmt::format(
                    "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"8\" fill=\"none\" stroke=\"#c00\" "
                    "stroke-width=\"2\"/>",
                    x, y);
        }
        std::sort(front.begin(), front.end());
        std::string line;
        for (const auto& [x, y] : front) line += fmt::format("{:.1f},{:.1f} ", x, y);
        svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"#1b3a5c\"/>", line);
    }
    return svg + "</svg>";
}

std::string quality_budget_summary(const Json& r, const std::filesystem::path& md) {
    const Json& best = r["best_affordable"];
    const std::string answer =
        best.is_null()
            ? std::string("no setting is affordable")
            : fmt::format(
                  "best affordable: {} (distinguishability {}, the paper's software {}, float {}; "
                  "{:.2f} frames/s)",
                  setting_name(r, best.get<size_t>()), num(r["points"][best.get<size_t>()]["distinguishability"]),
                  num(r["points"][0]["distinguishability"]), num(r["best_float_distinguishability"]),
                  r["points"][best.get<size_t>()]["timing"]["fps"].get<double>());
    return fmt::format("surfvp: quality-budget: {} settings; {}; report in {}", r["points"].size(), answer,
                       md.string());
}

}  // namespace surfvp
