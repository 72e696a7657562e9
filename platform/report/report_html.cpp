#include "platform/report/report_html.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "platform/report/correlation.h"
#include "platform/report/html_charts.h"
#include "platform/report/report.h"
#include "platform/report/run_summary.h"

namespace surfvp {

namespace {

using Json = nlohmann::ordered_json;

std::string esc(const std::string& text) { return xml_escape(text); }

// A table: a header row and rows of cells (already escaped where they hold text).
std::string table(const std::string& id, const std::vector<std::string>& head,
                  const std::vector<std::vector<std::string>>& rows) {
    std::string html = fmt::format("<table id=\"{}\">", id);
    if (!head.empty()) {
        html += "<tr>";
        for (const std::string& h : head) html += "<th>" + esc(h) + "</th>";
        html += "</tr>";
    }
    for (const auto& row : rows) {
        html += "<tr>";
        for (const std::string& c : row) html += "<td>" + c + "</td>";
        html += "</tr>";
    }
    return html + "</table>";
}

std::string section(const std::string& id, const std::string& title, const std::string& body) {
    return body.empty() ? "" : fmt::format("<section id=\"{}\"><h2>{}</h2>{}</section>", id, esc(title), body);
}

std::string fps(double v) { return fmt::format("{:.2f} frames/s", v); }
std::string pct(double share) { return fmt::format("{:+.1f} %", 100 * share); }

// 1. The verdict: the statement, the figures behind it, the chain of limits, the break-even.
std::string verdict_section(const Json& r) {
    const RunSummary run = RunSummary::of(r);
    const std::string answer = answer_line(r);
    std::string html = fmt::format("<p class=\"answer {}\"><b>{}: {}</b></p>", run.passed ? "met" : "missed",
                                   esc(run.result()), esc(answer.empty() ? "no frame rate in this run" : answer));
    std::vector<std::vector<std::string>> rows;
    if (run.fps > 0) rows.push_back({"frames/s (steady state)", fps(run.fps)});
    if (run.budget_met)
        rows.push_back({"budget", fmt::format("{} ({}; margin {})", fps(run.budget_fps),
                                              *run.budget_met ? "met" : "MISSED", pct(run.fps / run.budget_fps - 1))});
    if (r.contains("limit"))
        rows.push_back({"limited by",
                        esc(r["limit"]["resource"].get<std::string>() + " (" + r["limit"]["cause"].get<std::string>() +
                            "): " + r["limit"]["reason"].get<std::string>())});
    if (run.latency_ms > 0) rows.push_back({"latency", fmt::format("{:.2f} ms", run.latency_ms)});
    if (run.keypoints_per_frame > 0)
        rows.push_back({"keypoints per frame", fmt::format("{:.1f}", run.keypoints_per_frame)});
    if (r.contains("failure")) rows.push_back({"failure", esc(r["failure"].get<std::string>())});
    html += table("summary", {}, rows);
    const Json v = r.value("verdict", Json::object());
    if (v.contains("chain") && !v["chain"].empty()) {
        std::vector<std::vector<std::string>> chain;
        for (const Json& s : v["chain"]) {
            std::string relieved;
            for (const Json& x : s["relieved"])
                relieved += (relieved.empty() ? "" : ", ") + x.value("parameter", "") + " = " + x.value("value", "");
            chain.push_back({esc(s["resource"].get<std::string>() + " (" + s["cause"].get<std::string>() + ")"),
                             fps(s["fps"].get<double>()),
                             s["alone_fps"].is_null() ? "-" : fps(s["alone_fps"].get<double>()),
                             s["headroom"].is_null() ? "-" : pct(s["headroom"].get<double>()),
                             relieved.empty() ? "the scenario as it is" : esc(relieved)});
        }
        html += "<h3>The chain of limits</h3>" +
                table("chain", {"limit", "frames/s", "it alone allows", "headroom", "with"}, chain);
    }
    if (v.contains("break_even") && !v["break_even"].empty()) {
        std::vector<std::vector<std::string>> be;
        for (const Json& b : v["break_even"]) {
            const Json& check = b.value("check", Json::object());
            be.push_back({esc(b["parameter"].get<std::string>()), esc(b["default"].get<std::string>()),
                          esc(b["value"].is_string() ? b["value"].get<std::string>() : std::string("none found")),
                          check.contains("fps") ? fps(check["fps"].get<double>()) : "-",
                          check.contains("met") ? (check["met"].get<bool>() ? "met" : "MISSED") : "-"});
        }
        html += "<h3>Break-even: the value that meets the budget</h3>" +
                table("break_even", {"parameter", "default", "break-even", "whole run at it", "budget"}, be);
    }
    return html;
}

// 2. How sure: the unknowns one at a time (the tornado) and jointly (their distribution).
std::string doubt_section(const Json& r, const Json& figures) {
    if (!r.contains("verdict")) return "";
    const Json& v = r["verdict"];
    std::string html;
    if (v.contains("band"))
        html += fmt::format(
            "<p id=\"band\" data-low=\"{0:g}\" data-high=\"{1:g}\">The unknowns one at a time move the rate from "
            "<b>{2}</b> to <b>{3}</b>; {4} of them alone flip the verdict.</p>",
            v["band"]["low_fps"].get<double>(), v["band"]["high_fps"].get<double>(), fps(v["band"]["low_fps"]),
            fps(v["band"]["high_fps"]), v["band"]["flipping"].size());
    if (figures.contains("tornado_svg"))
        html += "<div class=\"figure\">" + figures["tornado_svg"].get<std::string>() + "</div>";
    if (v.contains("doubt") && v["doubt"].contains("fps")) {
        const Json& d = v["doubt"];
        html += fmt::format(
            "<p id=\"joint\" data-p5=\"{0:g}\" data-p95=\"{1:g}\" data-probability=\"{2:g}\">Over the {3} unknowns "
            "jointly ({4} points), the rate lies between <b>{5}</b> and <b>{6}</b> (5th to 95th percentile); the "
            "budget is met with probability <b>{7:.0f} %</b>.</p>",
            d["fps"]["p5"].get<double>(), d["fps"]["p95"].get<double>(), d.value("probability_met", 0.0),
            d.value("unknowns", 0), d.value("points", 0), fps(d["fps"]["p5"]), fps(d["fps"]["p95"]),
            100 * d.value("probability_met", 0.0));
        html += "<div class=\"figure\">" + distribution_chart(v) + "</div>";
        if (d.contains("sensitivity") && !d["sensitivity"].empty()) {
            std::vector<std::vector<std::string>> rows;
            for (size_t i = 0; i < std::min<size_t>(8, d["sensitivity"].size()); ++i) {
                const Json& s = d["sensitivity"][i];
                rows.push_back({esc(s["parameter"].get<std::string>()),
                                fmt::format("{:.0f} %", 100 * s["first_order"].get<double>()),
                                fmt::format("{:.0f} %", 100 * s["total"].get<double>())});
            }
            html += "<h3>What the doubt comes from</h3>" +
                    table("sensitivity", {"unknown", "share of the variance alone", "with its interactions"}, rows);
        }
    }
    return html;
}

// 3. What you can change: design choices (their effect on the rate) and software settings.
std::string changes_section(const Json& r) {
    if (!r.contains("verdict")) return "";
    const Json& v = r["verdict"];
    std::string html;
    if (v.contains("changes") && v["changes"].contains("axes")) {
        std::vector<std::vector<std::string>> rows;
        for (const Json& a : v["changes"]["axes"]) {
            auto side = [](const Json& s) {
                return s.contains("fps") && !s["fps"].is_null()
                           ? esc(s["value"].get<std::string>()) + ": " + fps(s["fps"].get<double>())
                           : esc(s.value("value", "")) + ": the scenario's";
            };
            rows.push_back({esc(a["parameter"].get<std::string>()), esc(a["value"].get<std::string>()), side(a["low"]),
                            side(a["high"]), esc(a.value("why", ""))});
        }
        html += "<h3>Design choices</h3>" +
                table("design_choices", {"parameter", "now", "one way", "the other", "why it may change"}, rows);
    }
    if (v.contains("software") && !v["software"].empty()) {
        std::vector<std::vector<std::string>> rows;
        for (const Json& s : v["software"])
            rows.push_back({esc(s["setting"].get<std::string>()), fps(s["fps"].get<double>()),
                            fmt::format("{:.1f} ms", s.value("cpu_ms_per_frame", 0.0)),
                            esc(s.value("limit", Json("")).is_string() ? s["limit"].get<std::string>() : ""),
                            s.value("met", false) ? "met" : "MISSED"});
        html += "<h3>Software settings</h3>" +
                table("software", {"setting", "frames/s", "CPU per frame", "limit", "budget"}, rows);
    }
    return html;
}

// 5. Resources and power against the device and the power budget.
std::string costs_section(const Json& r) {
    if (!r.contains("fpga_resources") || !r.contains("power")) return "";
    const Json &f = r["fpga_resources"], &p = r["power"];
    std::string html =
        fmt::format("<p>{} on the {}; <b>{:.2f} W</b> against {:g} W ({}), {:.3f} J a frame.</p>",
                    f["fits"].get<bool>() ? "The configuration fits" : "<b>The configuration does not fit</b>",
                    esc(f["device"].get<std::string>()), p["watts"].get<double>(), p.value("budget_w", 0.0),
                    p.value("within_budget", false) ? "within" : "OVER", p.value("joules_per_frame", 0.0));
    html += "<div class=\"figure\">" + cost_chart(r) + "</div>";
    std::vector<std::vector<std::string>> rows;
    for (const auto& [block, b] : f["blocks"].items())
        rows.push_back({esc(block), fmt::format("{:g}", b.value("ramb36", 0.0)),
                        fmt::format("{:g}", b.value("dsp48e", 0.0)), fmt::format("{:g}", b.value("luts", 0.0)),
                        fmt::format("{:g}", b.value("ffs", 0.0)), esc(b.value("basis", ""))});
    html += table("fpga_blocks", {"block", "RAMB36", "DSP48E", "LUTs", "flip-flops", "from"}, rows);
    rows.clear();
    for (const auto& [block, b] : p["blocks"].items())
        rows.push_back({esc(block), fmt::format("{:.3f} W", b.value("watts", 0.0)), esc(b.value("basis", ""))});
    return html + table("power_blocks", {"block", "watts", "from"}, rows);
}

// The run's other outputs, linked (keypoint files as one line).
std::string outputs_section(const Json& r) {
    std::string items;
    size_t keypoint_files = 0;
    for (const Json& o : r.value("outputs", Json::array())) {
        const std::string file = o.get<std::string>();
        if (file == "report.html") continue;
        if (file.rfind("keypoints/", 0) == 0) {
            if (keypoint_files++ == 0)
                items += fmt::format("<li><a href=\"{0}\">keypoints/</a>: one file per frame (the first: {0})</li>",
                                     esc(file));
            continue;
        }
        items += fmt::format("<li><a href=\"{0}\">{0}</a></li>", esc(file));
    }
    return items.empty() ? "" : "<ul id=\"outputs\">" + items + "</ul>";
}

std::string keypoints_section(const Json& figures) {
    if (!figures.contains("first_frame_svg") || figures["first_frame_svg"].get<std::string>().empty()) return "";
    return "<div class=\"figure keypoints\">" + figures["first_frame_svg"].get<std::string>() +
           "</div><p class=\"legend\"><span style=\"color:#ff0000\">&#9711; red</span>: a dark blob (Laplacian +1); "
           "<span style=\"color:#0080ff\">&#9711; blue</span>: a bright blob (-1); each circle 2.5 scales wide, its "
           "stroke at the orientation: the colours of <code>surfvp draw</code>.</p>";
}

std::string figure(const std::string& svg) { return svg.empty() ? "" : "<div class=\"figure\">" + svg + "</div>"; }

const char* const kStyle =
    "body{font-family:sans-serif;margin:16px auto;max-width:1200px;padding:0 12px;line-height:1.35}"
    "table{border-collapse:collapse;margin:8px 0;max-width:100%}th,td{border:1px solid #ccc;padding:3px "
    "8px;text-align:left;vertical-align:top}th{background:#f4f4f4}.figure{margin:12px 0}svg.chart{display:block;"
    "width:100%;height:auto;max-width:1100px}.keypoints svg{max-width:100%;height:auto}.answer{font-size:18px}"
    ".answer.missed b{color:#b00}nav a{margin-right:10px}section{margin-top:22px}"
    "@media print{body{max-width:none;margin:0}nav{display:none}section{break-inside:avoid}a{color:black}"
    "svg.chart{max-width:100%}}";

}  // namespace

std::string report_html(const Json& r, const Json& figures) {
    const std::string name = r["scenario"]["name"];
    const std::vector<std::pair<std::string, std::string>> sections = {
        {"verdict", "The verdict"},
        {"doubt", "How sure"},
        {"changes", "What you can change"},
        {"correlation", "Correlation with the published chip"},
        {"costs", "FPGA resources and power"},
        {"timeline", "Timeline"},
        {"resources", "Each resource's frame"},
        {"buses", "Buses and DDR"},
        {"fifos", "FIFOs"},
        {"keypoints", "Keypoints on the first frame"},
        {"outputs", "The run's files"}};
    const bool frames = r.contains("workload") && r["workload"].contains("per_frame");
    const std::vector<std::string> bodies = {
        verdict_section(r),
        doubt_section(r, figures),
        changes_section(r),
        r.contains("correlation") ? correlation_html(r["correlation"]) : "",
        costs_section(r),
        frames ? figure(gantt_chart(r)) : "",
        r.contains("time_per_frame") ? figure(resource_chart(r["time_per_frame"])) : "",
        figure(bus_chart(r)),
        figure(fifo_charts(r)),
        keypoints_section(figures),
        outputs_section(r)};
    std::string nav, body;
    for (size_t i = 0; i < sections.size(); ++i) {
        if (bodies[i].empty()) continue;
        nav += fmt::format("<a href=\"#{}\">{}</a>", sections[i].first, esc(sections[i].second));
        body += section(sections[i].first, sections[i].second, bodies[i]);
    }
    return "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\"><head><meta charset=\"utf-8\"/>"
           "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/><title>surfvp: " +
           esc(name) + "</title><style>" + kStyle + "</style></head><body>" +
           fmt::format("<h1>surfvp run: {}</h1><p>{}</p><nav>{}</nav>", esc(name),
                       esc(r["scenario"]["description"].get<std::string>()), nav) +
           body + "<p>Every figure is report.json's; report.md has them all as tables.</p></body></html>\n";
}

}  // namespace surfvp
