#include "platform/sweep/sweep_results.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <set>

#include "models/common/atomic_file.h"
#include "platform/sweep/sweep_plan.h"

namespace surfvp {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// Which figures a row has, in the order the columns come.
std::vector<std::string> figure_columns(const std::vector<SweepRow>& rows) {
    std::vector<std::string> columns;
    for (const SweepRow& r : rows)
        for (const auto& [key, value] : r.figures.items())
            if (std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
    return columns;
}

std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string as_text(const Json& v) {
    if (v.is_null()) return "";
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number_float()) return fmt::format("{:.6g}", v.get<double>());
    return v.dump();
}

const char* status_of(const SweepRow& r) { return r.error.empty() ? (r.exit == 0 ? "passed" : "failed") : "error"; }

// A value's number for a plot: "75 MHz" -> 75; a word has none.
std::optional<double> number_in(const std::string& value) {
    const auto q = split_quantity(value);
    return q ? std::optional<double>(q->first) : std::nullopt;
}

// Frames/s against one axis: a marker per point that ran (filled: on the Pareto front), a line
// through the points that share every other axis's value, the budget dashed.
std::string axis_plot(const std::string& name, const std::string& axis, const std::vector<std::string>& axes,
                      const std::vector<SweepRow>& rows, const std::vector<bool>& front) {
    constexpr double W = 640, H = 400, L = 64, R = 16, T = 36, B = 48;
    std::vector<std::string> categories;  // the axis's values in first-seen order
    bool numeric = true;
    for (const SweepRow& r : rows) {
        const std::string v = r.params.value(axis, "");
        if (std::find(categories.begin(), categories.end(), v) == categories.end()) categories.push_back(v);
        numeric = numeric && number_in(v).has_value();
    }
    auto x_of = [&](const std::string& v) { return numeric ? *number_in(v) : double(std::find(categories.begin(), categories.end(), v) - categories.begin()); };
    double x0 = 1e300, x1 = -1e300, y1 = 0, budget = 0;
    for (const SweepRow& r : rows) {
        x0 = std::min(x0, x_of(r.params.value(axis, "")));
        x1 = std::max(x1, x_of(r.params.value(axis, "")));
        y1 = std::max(y1, r.figures.value("fps", 0.0));
        budget = std::max(budget, r.figures.value("budget_fps", 0.0));
    }
    y1 = std::max(y1, budget) * 1.1 + 1e-9;
    if (x1 <= x0) x1 = x0 + 1;
    auto px = [&](double x) { return L + (x - x0) / (x1 - x0) * (W - L - R); };
    auto py = [&](double y) { return H - B - y / y1 * (H - T - B); };
    std::string svg = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" "
                                  "font-size=\"12\"><rect width=\"100%\" height=\"100%\" fill=\"white\"/>"
                                  "<text x=\"{}\" y=\"20\" font-size=\"14\">{}: frames/s against {}</text>",
                                  W, H, L, name, axis);
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"black\"/><line x1=\"{0}\" y1=\"{3}\" x2=\"{0}\" "
                       "y2=\"{1}\" stroke=\"black\"/>",
                       L, H - B, W - R, T);
    for (int i = 0; i <= 4; ++i) {
        const double y = y1 * i / 4;
        svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{:.3g}</text>", L - 6, py(y) + 4, y);
    }
    std::set<double> ticks;
    for (const std::string& c : categories) ticks.insert(x_of(c));
    for (double t : ticks) {
        const std::string label = numeric ? fmt::format("{:.6g}", t) : categories[size_t(t)];
        svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>", px(t), H - B + 16, label);
    }
    const auto unit = rows.empty() ? std::nullopt : split_quantity(rows[0].params.value(axis, ""));
    const std::string unit_text = unit && !unit->second.empty() ? " (" + unit->second + ")" : "";
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}{}</text>", (L + W - R) / 2, H - 10, axis, unit_text);
    svg += fmt::format("<text x=\"14\" y=\"{}\" transform=\"rotate(-90 14 {})\" text-anchor=\"middle\">frames/s</text>",
                       (T + H - B) / 2, (T + H - B) / 2);
    if (budget > 0)
        svg += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#c00\" stroke-dasharray=\"6 4\"/>"
                           "<text x=\"{2}\" y=\"{3:.1f}\" text-anchor=\"end\" fill=\"#c00\">budget {4:g} frames/s</text>",
                           L, py(budget), W - R, py(budget) - 4, budget);
    // One line per combination of the other axes' values.
    std::map<std::string, std::vector<std::pair<double, double>>> lines;
    for (const SweepRow& r : rows) {
        if (!r.error.empty()) continue;
        std::string others;
        for (const std::string& a : axes)
            if (a != axis) others += a + "=" + r.params.value(a, "") + " ";
        lines[others].push_back({x_of(r.params.value(axis, "")), r.figures.value("fps", 0.0)});
    }
    std::vector<double> labelled;  // the heights of the line labels so far: one that would overlap is left out
    for (auto& [others, pts] : lines) {
        std::sort(pts.begin(), pts.end());
        std::string p;
        for (const auto& [x, y] : pts) p += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
        svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"#8aa\"><title>{}</title></polyline>", p, others);
        const double end_y = py(pts.back().second);
        if (others.empty() || std::any_of(labelled.begin(), labelled.end(), [&](double y) { return std::abs(y - end_y) < 12; }))
            continue;
        labelled.push_back(end_y);
        svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\" font-size=\"10\" fill=\"#466\">{}</text>",
                           px(pts.back().first) - 8, end_y - 6, others);
    }
    for (size_t i = 0; i < rows.size(); ++i) {
        const SweepRow& r = rows[i];
        if (!r.error.empty()) continue;
        svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" stroke=\"#1b3a5c\" fill=\"{}\"><title>{}: {:.3g} frames/s{}"
                           "</title></circle>",
                           px(x_of(r.params.value(axis, ""))), py(r.figures.value("fps", 0.0)), front[i] ? "#1b3a5c" : "white",
                           r.id, r.figures.value("fps", 0.0), front[i] ? " (Pareto front)" : "");
    }
    return svg + fmt::format("<text x=\"{}\" y=\"{}\">filled: on the Pareto front</text></svg>", W - R - 150, T - 4);
}

}  // namespace

Json sweep_figures(const Json& r) {
    Json f;
    f["fps"] = r.value("throughput_fps", 0.0);
    f["budget_fps"] = r.contains("budget") && r["budget"].is_object() ? r["budget"].value("fps", 0.0) : 0.0;
    f["budget_met"] = r.contains("budget") && r["budget"].is_object() ? Json(r["budget"].value("met", false)) : Json();
    f["latency_ms"] = r.value("latency_ms", 0.0);
    f["bottleneck"] = r.contains("limit") ? r["limit"].value("resource", "") : "";
    f["bottleneck_cause"] = r.contains("limit") ? r["limit"].value("cause", "") : "";
    if (r.contains("time_per_frame"))
        for (const auto& [resource, t] : r["time_per_frame"].items())
            f["busy." + resource] = t.value("busy_share", 0.0);
    if (r.contains("fpga_resources")) {
        const Json& fpga = r["fpga_resources"];
        f["bram36"] = fpga["total"]["ramb36"];
        f["dsp48e"] = fpga["total"]["dsp48e"];
        f["luts"] = fpga["total"]["luts"];
        f["fits"] = fpga["fits"];
    }
    f["keypoints_per_frame"] = r.value("keypoints_per_frame", 0.0);
    f["sim_time_s"] = r.value("sim_time_s", 0.0);
    f["passed"] = r.value("passed", false);
    return f;
}

std::vector<Objective> pareto_objectives(const std::vector<SweepRow>& rows) {
    std::vector<Objective> out{{"fps", true}};
    // Costs the rows carry (FPGA resources, power), when they do: lower is better.
    for (const char* cost : {"bram36", "dsp48e", "watts"})
        if (std::any_of(rows.begin(), rows.end(), [&](const SweepRow& r) { return r.figures.contains(cost); }))
            out.push_back({cost, false});
    return out;
}

std::vector<bool> pareto_front(const std::vector<SweepRow>& rows, const std::vector<Objective>& objectives) {
    constexpr double kTie = 1e-3;
    auto value = [&](const SweepRow& r, const Objective& o) {
        const double v = r.figures.value(o.figure, 0.0);
        return o.higher_is_better ? v : -v;
    };
    std::vector<bool> front(rows.size(), false);
    for (size_t i = 0; i < rows.size(); ++i) {
        if (!rows[i].error.empty()) continue;
        bool beaten = false;
        for (size_t j = 0; j < rows.size() && !beaten; ++j) {
            if (j == i || !rows[j].error.empty()) continue;
            // Figures within kTie of each other count as equal: a point 0.01 % faster at two
            // more block RAMs is not a trade-off a review weighs.
            bool all = true, one = false;
            for (const Objective& o : objectives) {
                const double a = value(rows[j], o), b = value(rows[i], o), tie = kTie * std::max(std::abs(a), std::abs(b));
                all = all && a >= b - tie;
                one = one || a > b + tie;
            }
            beaten = all && one;
        }
        front[i] = !beaten;
    }
    return front;
}

std::vector<std::string> write_sweep_results(const std::string& dir, const std::string& name,
                                             const std::vector<std::string>& axes, const std::vector<SweepRow>& rows) {
    const std::vector<Objective> objectives = pareto_objectives(rows);
    const std::vector<bool> front = pareto_front(rows, objectives);
    const std::vector<std::string> columns = figure_columns(rows);
    std::string csv = "point";
    for (const std::string& a : axes) csv += "," + csv_field(a);
    csv += ",status,exit";
    for (const std::string& c : columns) csv += "," + csv_field(c);
    csv += ",pareto,wall_s,error\n";
    Json points = Json::array();
    for (size_t i = 0; i < rows.size(); ++i) {
        const SweepRow& r = rows[i];
        csv += std::to_string(r.index);
        for (const std::string& a : axes) csv += "," + csv_field(r.params.value(a, ""));
        csv += fmt::format(",{},{}", status_of(r), r.exit);
        for (const std::string& c : columns) csv += "," + csv_field(r.figures.contains(c) ? as_text(r.figures[c]) : "");
        csv += fmt::format(",{},{:.3f},{}\n", front[i] ? 1 : 0, r.wall_s, csv_field(r.error));
        Json p = {{"point", r.index}, {"id", r.id}, {"params", r.params}, {"status", status_of(r)}, {"exit", r.exit}};
        if (!r.error.empty()) p["error"] = r.error;
        p["figures"] = r.figures;
        p["pareto"] = bool(front[i]);
        p["wall_s"] = r.wall_s;
        points.push_back(p);
    }
    Json objectives_json = Json::array();
    for (const Objective& o : objectives) objectives_json.push_back({{"figure", o.figure}, {"better", o.higher_is_better ? "higher" : "lower"}});
    const Json results = {{"sweep", name}, {"axes", axes}, {"pareto_objectives", objectives_json}, {"points", points}};
    std::vector<std::string> written{"results.csv", "results.json"};
    write_file_atomically((fs::path(dir) / "results.csv").string(), csv);
    write_file_atomically((fs::path(dir) / "results.json").string(), results.dump(2) + "\n");
    for (const std::string& axis : axes) {
        std::string file = "plot_" + axis + ".svg";
        std::replace(file.begin(), file.end(), '/', '_');
        write_file_atomically((fs::path(dir) / file).string(), axis_plot(name, axis, axes, rows, front));
        written.push_back(file);
    }
    return written;
}

}  // namespace surfvp
