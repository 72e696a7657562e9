#include "platform/report/report_html.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "platform/report/correlation.h"
#include "platform/report/run_summary.h"

namespace surfvp {

namespace {

using Json = nlohmann::ordered_json;

constexpr double kWidth = 960, kLeft = 190, kRight = 20;  // chart geometry in px
const char* const kColours[] = {"#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#76b7b2", "#edc948", "#b07aa1", "#9c755f"};

std::string colour(size_t i) { return kColours[i % (sizeof kColours / sizeof *kColours)]; }

// A time axis from 0 to `end_ms` along the chart's width at height `y`, with ~8 ticks.
std::string time_axis(double end_ms, double y) {
    const double span = kWidth - kLeft - kRight;
    const double raw = end_ms / 8, scale = std::pow(10.0, std::floor(std::log10(std::max(raw, 1e-9))));
    const double step = raw / scale < 2 ? 2 * scale : raw / scale < 5 ? 5 * scale : 10 * scale;
    std::string svg =
        fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#333\"/>", kLeft, y, kWidth - kRight, y);
    for (double t = 0; t <= end_ms + 1e-9; t += step) {
        const double x = kLeft + span * t / end_ms;
        svg += fmt::format(
            "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#333\"/>"
            "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:g} ms</text>",
            x, y, y + 4, y + 16, t);
    }
    return svg;
}

std::string svg_open(const std::string& id, double height, const std::string& title) {
    return fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"{}\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
        "font-family=\"sans-serif\" font-size=\"12\"><text x=\"0\" y=\"16\" font-size=\"15\" "
        "font-weight=\"bold\">{}</text>",
        id, kWidth, height, kWidth, height, xml_escape(title));
}

double at_x(double ms, double end_ms) { return kLeft + (kWidth - kLeft - kRight) * ms / end_ms; }

// The first frames across the chip: each pair's IIG and FHG from the task's start, PLB2's
// busy share (their DMA) per time bin, the CPU's descriptors after the determinants.
std::string gantt(const Json& r) {
    const Json& frames = r["workload"]["per_frame"];
    const size_t pairs = std::max<size_t>(1, r.contains("accelerator_pairs") ? r["accelerator_pairs"].size() : 1);
    const size_t shown = std::min(frames.size(), 2 * pairs + 2);
    double end_ms = 0;
    for (size_t i = 0; i < shown; ++i) end_ms = std::max(end_ms, frames[i]["done_ms"].get<double>());
    if (end_ms <= 0) return "";
    std::vector<std::string> rows;
    for (size_t k = 0; k < pairs; ++k) {
        rows.push_back(pairs > 1 ? fmt::format("IIG {}", k) : "IIG");
        rows.push_back(pairs > 1 ? fmt::format("FHG {}", k) : "FHG");
    }
    rows.push_back("PLB2 (their DMA)");
    rows.push_back("CPU (descriptors)");
    const double row_h = 26, top = 30, height = top + rows.size() * row_h + 44;
    std::string svg = svg_open("gantt", height, fmt::format("The first {} frames across the chip", shown));
    for (size_t i = 0; i < rows.size(); ++i)
        svg += fmt::format("<text x=\"0\" y=\"{:.1f}\">{}</text>", top + i * row_h + 17, xml_escape(rows[i]));
    auto bar = [&](size_t row, size_t frame, double from, double to, const std::string& what) {
        const double x0 = at_x(from, end_ms), x1 = at_x(to, end_ms), y = top + row * row_h + 3;
        svg += fmt::format(
            "<rect class=\"task\" data-frame=\"{}\" data-start-ms=\"{:.3f}\" data-end-ms=\"{:.3f}\" x=\"{:.1f}\" "
            "y=\"{:.1f}\" width=\"{:.1f}\" height=\"{}\" fill=\"{}\" opacity=\"0.85\"><title>frame {}: {} "
            "{:.2f} to {:.2f} ms</title></rect>",
            frame, from, to, x0, y, std::max(1.0, x1 - x0), row_h - 6, colour(frame), frame, what, from, to);
        if (x1 - x0 > 24)
            svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"white\">{}</text>", x0 + 4, y + 14, frame);
    };
    for (size_t i = 0; i < shown; ++i) {
        const Json& f = frames[i];
        const size_t k = i % pairs;
        const double start = f["start_ms"], integral = f["integral_done_ms"], determinants = f["determinants_done_ms"];
        bar(2 * k, i, start, integral, "integral image");
        bar(2 * k + 1, i, start, determinants, "determinants");
        bar(rows.size() - 1, i, determinants, f["done_ms"], "descriptors");
    }
    // PLB2's busier direction per bin. A long run's series have widened their bins, each at
    // its own time: each is read at the finer one's bins.
    const Json& plb2 = r["buses"]["plb2"];
    const Json& read = plb2["read"]["busy_series"];
    const Json& write = plb2["write"]["busy_series"];
    auto share_at = [](const Json& series, double t_ms) {
        const size_t b = size_t(t_ms / (series["bin_s"].get<double>() * 1e3));
        return b < series["values"].size() ? series["values"][b].get<double>() : 0.0;
    };
    const double bin_ms = std::min(read["bin_s"].get<double>(), write["bin_s"].get<double>()) * 1e3;
    const double y = top + (rows.size() - 2) * row_h + 3;
    double peak = 0;
    for (const Json* s : {&read, &write})
        for (const auto& v : (*s)["values"]) peak = std::max(peak, v.get<double>());
    for (size_t b = 0; b * bin_ms < end_ms; ++b) {
        const double mid = (b + 0.5) * bin_ms, share = std::max(share_at(read, mid), share_at(write, mid));
        if (share <= 0) continue;
        const double x0 = at_x(b * bin_ms, end_ms), x1 = at_x(std::min(end_ms, (b + 1) * bin_ms), end_ms);
        svg += fmt::format(
            "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{}\" fill=\"#1b3a5c\" opacity=\"{:.3f}\">"
            "<title>PLB2 {:.1f} % busy</title></rect>",
            x0, y, x1 - x0, row_h - 6, share / peak, 100 * share);
    }
    svg += time_axis(end_ms, top + rows.size() * row_h + 4);
    svg += fmt::format(
        "<text x=\"{}\" y=\"{}\">PLB2: darker is busier (hover a bin for its share); CPU: each frame's "
        "descriptors after its determinants</text>",
        kLeft, height - 2);
    return svg + "</svg>";
}

// Each resource's frame period as busy, each wait and idle.
std::string resource_bars(const Json& table) {
    const double row_h = 24, top = 30, height = top + table.size() * row_h + 50;
    double period = 0;
    for (const auto& [name, row] : table.items()) period = std::max(period, row["period_ms"].get<double>());
    if (period <= 0) return "";
    std::string svg = svg_open("resources", height, "Where each resource's frame goes: busy, waiting, idle");
    const char* const wait_colours[] = {"#f28e2b", "#e15759", "#edc948", "#b07aa1"};
    size_t i = 0;
    for (const auto& item : table.items()) {
        const std::string& name = item.key();  // a local the lambda below may capture (a binding may not)
        const Json& row = item.value();
        const double y = top + i++ * row_h;
        svg += fmt::format("<text x=\"0\" y=\"{:.1f}\">{} ({:.1f} % busy)</text>", y + 15, xml_escape(name),
                           100 * row["busy_share"].get<double>());
        double at = 0;
        auto piece = [&](double ms, const std::string& fill, const std::string& what) {
            if (ms <= 0) return;
            // A CPU waits while it is busy elsewhere in the frame (its sum can pass the period): clipped.
            if (at >= period) return;
            const double x0 = at_x(at, period), x1 = at_x(std::min(period, at + ms), period);
            svg += fmt::format(
                "<rect class=\"{}\" data-resource=\"{}\" data-ms=\"{:.3f}\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" "
                "height=\"{}\" fill=\"{}\"><title>{}: {} {:.2f} ms</title></rect>",
                what == "busy" || what == "idle" ? what : "wait", xml_escape(name), ms, x0, y + 3,
                std::max(0.5, x1 - x0), row_h - 6, fill, xml_escape(name), xml_escape(what), ms);
            at += ms;
        };
        piece(row["busy_ms"], "#4e79a7", "busy");
        size_t w = 0;
        for (const auto& [cause, ms] : row["waits_ms"].items()) piece(ms, wait_colours[w++ % 4], "waiting: " + cause);
        piece(row["idle_ms"], "#cccccc", "idle");
    }
    svg += time_axis(period, top + table.size() * row_h + 4);
    svg += fmt::format(
        "<text x=\"{}\" y=\"{}\">blue: busy; warm colours: waiting (hover for the cause); grey: idle; one frame "
        "period = {:.2f} ms</text>",
        kLeft, height - 4, period);
    return svg + "</svg>";
}

struct Line {
    std::string name;
    const Json* series;  // {"bin_s", "values"}
};

// Figures per time bin as step lines over the run, scaled to the largest (or to `y_max`).
std::string line_chart(const std::string& id, const std::string& title, const std::vector<Line>& lines, double y_max,
                       const std::string& y_unit, double end_ms) {
    double peak = 0;
    for (const Line& l : lines)
        for (const auto& v : (*l.series)["values"]) peak = std::max(peak, v.get<double>());
    if (end_ms <= 0) return "";
    const double top = 30, plot_h = 150, height = top + plot_h + 50;
    const double scale = y_max > 0 ? y_max : std::max(peak, 1.0);
    std::string svg = svg_open(id, height, title);
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"#333\"/><text x=\"{3}\" y=\"{4}\" "
        "text-anchor=\"end\">{5:g} {6}</text><text x=\"{3}\" y=\"{2}\" text-anchor=\"end\">0</text>",
        kLeft, top, top + plot_h, kLeft - 4, top + 10, y_max > 0 ? y_max * 100 : scale,
        y_max > 0 ? "%" : xml_escape(y_unit));
    const double spacing = (kWidth - kLeft) / double(lines.size());
    size_t i = 0;
    for (const Line& l : lines) {
        const double bin_ms = (*l.series)["bin_s"].get<double>() * 1e3;
        std::string points;
        double line_peak = 0;
        size_t b = 0;
        for (const auto& v : (*l.series)["values"]) {
            const double y = top + plot_h * (1 - std::min(1.0, v.get<double>() / scale));
            points += fmt::format("{:.1f},{:.1f} {:.1f},{:.1f} ", at_x(b * bin_ms, end_ms), y,
                                  at_x((b + 1) * bin_ms, end_ms), y);
            line_peak = std::max(line_peak, v.get<double>());
            ++b;
        }
        svg += fmt::format(
            "<polyline class=\"series\" data-name=\"{}\" data-peak=\"{:g}\" data-bins=\"{}\" points=\"{}\" "
            "fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>",
            xml_escape(l.name), line_peak, b, points, colour(i));
        svg += fmt::format(
            "<rect x=\"{}\" y=\"{}\" width=\"10\" height=\"10\" fill=\"{}\"/><text x=\"{}\" y=\"{}\">{} (peak "
            "{:g}{})</text>",
            kLeft + 10 + spacing * double(i), height - 14, colour(i), kLeft + 24 + spacing * double(i), height - 5,
            xml_escape(l.name), y_max > 0 ? line_peak * 100 : line_peak, y_max > 0 ? " %" : "");
        ++i;
    }
    svg += time_axis(end_ms, top + plot_h);
    return svg + "</svg>";
}

std::string bus_chart(const Json& r) {
    std::vector<Line> lines;
    for (const auto& [bus, b] : r["buses"].items())
        for (const char* path : {"read", "write"})
            if (b[path].contains("busy_series") && b[path]["bytes"].get<double>() > 0)
                lines.push_back({bus + " " + path, &b[path]["busy_series"]});
    if (r.contains("memory") && r["memory"].contains("busy_series"))
        lines.push_back({"DDR", &r["memory"]["busy_series"]});
    return line_chart("buses", "Bus and DDR utilisation over the run (busy share per time bin)", lines, 1.0, "",
                      r["sim_time_s"].get<double>() * 1e3);
}

std::string fifo_charts(const Json& r) {
    if (!r.contains("fhg")) return "";
    const Json& fhg = r["fhg"].is_array() ? r["fhg"][0] : r["fhg"];
    if (!fhg.contains("line_fifo_series")) return "";
    return line_chart("line_fifo", "The FHG's line FIFO over the run (integral lines held, highest per time bin)",
                      {{"line FIFO", &fhg["line_fifo_series"]}}, 0, "lines", r["sim_time_s"].get<double>() * 1e3) +
           line_chart("maxima_fifo",
                      "The FHG's maxima FIFO over the run (candidates waiting for the CPU, highest per time bin)",
                      {{"maxima FIFO", &fhg["maxima_fifo_series"]}}, 0, "entries", r["sim_time_s"].get<double>() * 1e3);
}

// The figures the verdict rests on, as a table.
std::string summary(const Json& r) {
    std::string rows;
    auto row = [&](const std::string& k, const std::string& v) {
        rows += fmt::format("<tr><th>{}</th><td>{}</td></tr>", xml_escape(k), xml_escape(v));
    };
    if (r.contains("throughput_fps"))
        row("throughput", fmt::format("{:.2f} frames/s", r["throughput_fps"].get<double>()));
    if (r.contains("budget") && !r["budget"].is_null())
        row("budget", fmt::format("{:.2f} frames/s: {}", r["budget"]["fps"].get<double>(),
                                  r["budget"]["met"].get<bool>() ? "met" : "MISSED"));
    if (r.contains("limit"))
        row("limited by", r["limit"]["resource"].get<std::string>() + ": " + r["limit"]["reason"].get<std::string>());
    if (r.contains("latency_ms")) row("latency", fmt::format("{:.2f} ms", r["latency_ms"].get<double>()));
    if (r.contains("keypoints_per_frame"))
        row("keypoints per frame", fmt::format("{:.1f}", r["keypoints_per_frame"].get<double>()));
    if (r.contains("threshold_rule"))
        row("determinant threshold",
            fmt::format("{:.3f}: {}", r["threshold"].get<double>(), r["threshold_rule"].get<std::string>()));
    const Json verdict = r.value("verdict", Json::object());
    if (verdict.contains("chain") && !verdict["chain"].empty()) {
        std::string chain;
        for (const Json& step : verdict["chain"])
            chain +=
                (chain.empty() ? "" : ", then ") + step["resource"].get<std::string>() +
                (step["headroom"].is_null() ? "" : fmt::format(" ({:+.1f} %)", 100 * step["headroom"].get<double>()));
        row("chain of limits (headroom)", chain);
    }
    if (verdict.contains("doubt") && verdict["doubt"].contains("fps")) {
        const Json& d = verdict["doubt"];
        row("the unknowns jointly",
            fmt::format("{:.2f} / {:.2f} / {:.2f} frames/s (5th / 50th / 95th percentile); budget met with "
                        "probability {:.0f} %",
                        d["fps"]["p5"].get<double>(), d["fps"]["p50"].get<double>(), d["fps"]["p95"].get<double>(),
                        100 * d.value("probability_met", 0.0)));
    }
    if (verdict.contains("band"))
        row("the unknowns one at a time",
            fmt::format("{:.2f} to {:.2f} frames/s", verdict["band"]["low_fps"].get<double>(),
                        verdict["band"]["high_fps"].get<double>()));
    return "<table id=\"summary\">" + rows + "</table>";
}

}  // namespace

std::string report_html(const Json& r, const std::string& first_frame_svg) {
    const std::string name = r["scenario"]["name"];
    std::string verdict = RunSummary::of(r).result();
    if (r.contains("verdict") && r["verdict"].contains("statement"))
        verdict = r["verdict"]["statement"].get<std::string>();
    std::string body =
        fmt::format("<h1>surfvp run: {}</h1><p>{}</p><p class=\"verdict\"><b>{}</b></p>", xml_escape(name),
                    xml_escape(r["scenario"]["description"].get<std::string>()), xml_escape(verdict));
    body += summary(r);
    if (r.contains("correlation")) body += correlation_html(r["correlation"]);
    auto section = [&](const std::string& svg) {
        if (!svg.empty()) body += "<div class=\"chart\">" + svg + "</div>";
    };
    if (r.contains("workload") && r["workload"].contains("per_frame")) section(gantt(r));
    if (r.contains("time_per_frame")) section(resource_bars(r["time_per_frame"]));
    section(bus_chart(r));
    section(fifo_charts(r));
    if (!first_frame_svg.empty())
        body += "<h2>Keypoints on the first frame</h2><div class=\"chart\">" + first_frame_svg + "</div>";
    body += "<p>The figures are report.json's; report.md has them all as tables.</p>";
    return "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\"><head><meta "
           "charset=\"utf-8\"/><title>surfvp: " +
           xml_escape(name) +
           "</"
           "title><style>body{font-family:sans-serif;margin:20px;max-width:1000px}table{border-collapse:collapse;"
           "margin:10px 0}"
           "th,td{border:1px solid #ccc;padding:3px 8px;text-align:left}th{background:#f4f4f4}.chart{margin:18px 0}"
           ".verdict{font-size:18px}</style></head><body>" +
           body + "</body></html>\n";
}

}  // namespace surfvp
