#include "platform/sweep/sweep_results.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <set>

#include "models/host/atomic_file.h"
#include "platform/report/figure_format.h"
#include "platform/report/json_input.h"
#include "platform/report/run_summary.h"
#include "platform/sweep/sweep_plots.h"

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

// A point that missed its budget or broke ran: its row is a result. "error" is a point that
// could not run.
const char* status_of(const SweepRow& r) {
    switch (r.exit) {
        case kExitOk:
            return "passed";
        case kExitFailed:
            return "missed";
        case kExitBroken:
            return "broken";
        default:
            return "error";
    }
}

// results.md: the points as a person reads them, each figure through its unit.
std::string results_markdown(const std::string& name, const std::vector<std::string>& axes,
                             const std::vector<SweepRow>& rows, const std::vector<bool>& front,
                             const std::vector<Objective>& objectives) {
    std::vector<std::string> shown;
    for (const char* c : {"fps", "bottleneck", "latency_ms", "bram36", "dsp48e", "luts", "fits", "closes", "watts",
                          "repeatability", "precision", "distinguishability"})
        if (std::any_of(rows.begin(), rows.end(), [&](const SweepRow& r) { return r.figures.contains(c); }))
            shown.emplace_back(c);
    std::vector<std::string> weighed;
    for (const Objective& o : objectives) weighed.push_back(o.figure);
    const size_t on_front = size_t(std::count(front.begin(), front.end(), true));
    std::string md = fmt::format(
        "# Sweep {}\n\n{} points; {} on the Pareto front of {} (only points that ran whole, fit the device "
        "and close their clocks are weighed). Status: passed, missed (a budget or goal: a design that does not fit "
        "or close misses), broken (the run broke), error (could not run).\n\n| point |",
        name, rows.size(), on_front, fmt::join(weighed, ", "));
    std::string rule = "|---:|";
    for (const std::string& a : axes) md += " " + a + " |", rule += "---|";
    md += " status |", rule += "---|";
    for (const std::string& c : shown) {
        const std::string unit = RunSummary::unit_of(c);
        md += " " + (c == "bottleneck" ? std::string("limit") : c) + " |";
        rule += unit.empty() ? "---|" : "---:|";
    }
    md += " front |\n" + rule + "---|\n";
    for (size_t i = 0; i < rows.size(); ++i) {
        const SweepRow& r = rows[i];
        md += fmt::format("| {} |", r.index);
        for (const std::string& a : axes) md += " " + r.params.value(a, "") + " |";
        md += fmt::format(" {} |", status_of(r));
        for (const std::string& c : shown)
            md += " " + (r.figures.contains(c) ? format_figure(r.figures[c], RunSummary::unit_of(c)) : "-") + " |";
        md += front[i] ? " yes |\n" : " |\n";
    }
    return md;
}

}  // namespace

std::vector<Objective> pareto_objectives(const std::vector<SweepRow>& rows) {
    std::vector<Objective> out{{"fps", true}};
    // Feature quality, when measured: higher is better.
    for (const char* quality : {"repeatability", "precision", "distinguishability"})
        if (std::any_of(rows.begin(), rows.end(), [&](const SweepRow& r) { return r.figures.contains(quality); }))
            out.push_back({quality, true});
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
    // Only points that ran whole, fit the device and close their clocks trade off: one that
    // could not be built is no design, whatever its figures.
    auto candidate = [](const SweepRow& r) {
        auto is_false = [&r](const char* key) { return r.figures.contains(key) && r.figures[key] == false; };
        return r.error.empty() && r.exit != kExitBroken && !is_false("fits") && !is_false("closes");
    };
    std::vector<bool> front(rows.size(), false);
    for (size_t i = 0; i < rows.size(); ++i) {
        if (!candidate(rows[i])) continue;
        bool beaten = false;
        for (size_t j = 0; j < rows.size() && !beaten; ++j) {
            if (j == i || !candidate(rows[j])) continue;
            // Figures within kTie of each other count as equal: a point 0.01 % faster at two
            // more block RAMs is not a trade-off a review weighs.
            bool all = true, one = false;
            for (const Objective& o : objectives) {
                const double a = value(rows[j], o), b = value(rows[i], o),
                             tie = kTie * std::max(std::abs(a), std::abs(b));
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
                                             const std::vector<std::string>& axes, const std::vector<SweepRow>& rows,
                                             const Json& notes) {
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
    for (const Objective& o : objectives)
        objectives_json.push_back({{"figure", o.figure}, {"better", o.higher_is_better ? "higher" : "lower"}});
    Json results = {{"sweep", name}, {"axes", axes}};
    for (const auto& [key, value] : notes.items()) results[key] = value;
    results["pareto_objectives"] = objectives_json;
    results["points"] = points;
    std::vector<std::string> written{"results.md", "results.csv", "results.json"};
    write_file_atomically((fs::path(dir) / "results.md").string(),
                          results_markdown(name, axes, rows, front, objectives));
    write_file_atomically((fs::path(dir) / "results.csv").string(), csv);
    write_file_atomically((fs::path(dir) / "results.json").string(), results.dump(2) + "\n");
    for (const std::string& axis : axes) {
        std::string file = "plot_" + axis + ".svg";
        std::replace(file.begin(), file.end(), '/', '_');
        write_file_atomically((fs::path(dir) / file).string(), axis_plot(name, axis, axes, rows, front));
        written.push_back(file);
    }
    if (!objectives.back()
             .higher_is_better) {  // against watts when the rows have them: the cost that moves with every axis
        const std::string cost = objectives.back().figure;
        write_file_atomically((fs::path(dir) / "pareto.svg").string(), front_plot(name, cost, rows, front));
        written.push_back("pareto.svg");
    }
    return written;
}

}  // namespace surfvp
