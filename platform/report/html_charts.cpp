#include "platform/report/html_charts.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <string>
#include <utility>
#include <vector>

#include "models/host/xml_text.h"
#include "platform/report/chart_ticks.h"

namespace surfvp {
namespace {

using Json = nlohmann::ordered_json;

constexpr double kWidth = 960, kLeft = 190, kRight = 24;  // the charts' coordinates (their viewBox)
const char* const kColours[] = {"#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#76b7b2", "#edc948", "#b07aa1", "#9c755f"};

std::string colour(size_t i) { return kColours[i % (sizeof kColours / sizeof *kColours)]; }

struct Key {
    std::string colour, label;
};

// An SVG that takes the page's width: drawn in kWidth units, scaled by the browser.
std::string svg_open(const std::string& id, double height, const std::string& title) {
    return fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"{0}\" class=\"chart\" viewBox=\"0 0 {1} {2}\" width=\"100%\" "
        "preserveAspectRatio=\"xMinYMin meet\" font-family=\"sans-serif\" font-size=\"13\"><text x=\"0\" y=\"16\" "
        "font-size=\"15\" font-weight=\"bold\">{3}</text>",
        id, kWidth, height, xml_escape(title));
}

double at_x(double v, const Ticks& x) { return kLeft + (kWidth - kLeft - kRight) * (v - x.lo()) / (x.hi() - x.lo()); }

// A horizontal axis at height `y`: round ticks over the data, each labelled with `unit`.
std::string x_axis(const Ticks& x, double y, const std::string& unit) {
    std::string svg =
        fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#333\"/>", kLeft, y, kWidth - kRight, y);
    for (const double t : x.at)  // the unit once, after the last
        svg += fmt::format(
            "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#333\"/>"
            "<text class=\"tick\" x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"{4}\">{5}{6}</text>",
            at_x(t, x), y, y + 4, y + 17, t == x.at.back() ? "end" : "middle", tick_label(t, x.step),
            t == x.at.back() ? " " + xml_escape(unit) : "");
    return svg;
}

// Legend rows from `y` down: a swatch and a label each, wrapped at the chart's width.
std::string legend(const std::vector<Key>& keys, double y, double& bottom) {
    std::string svg = "<g class=\"legend\">";
    double x = kLeft, row = y;
    for (const Key& k : keys) {
        const double w = 26 + 7.2 * double(k.label.size());
        if (x + w > kWidth - kRight && x > kLeft) x = kLeft, row += 18;
        svg += fmt::format(
            "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"12\" height=\"12\" fill=\"{}\" stroke=\"#333\" "
            "stroke-width=\"0.5\"/><text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>",
            x, row - 10, k.colour, x + 16, row, xml_escape(k.label));
        x += w;
    }
    bottom = row + 8;
    return svg + "</g>";
}

// The top of row i of a chart of rows (a bar 20 high, 26 apart).
double row_y(size_t i) { return 30 + double(i) * 26; }

}  // namespace

std::string gantt_chart(const Json& r) {
    const Json& frames = r["workload"]["per_frame"];
    const size_t pairs = std::max<size_t>(1, r.contains("accelerator_pairs") ? r["accelerator_pairs"].size() : 1);
    const size_t shown = std::min(frames.size(), 2 * pairs + 2);
    double end_ms = 0;
    for (size_t i = 0; i < shown; ++i) end_ms = std::max(end_ms, frames[i]["done_ms"].get<double>());
    if (end_ms <= 0) return "";
    const Ticks x = round_ticks(0, end_ms, 8);
    std::vector<std::string> rows;
    for (size_t k = 0; k < pairs; ++k) {
        rows.push_back(pairs > 1 ? fmt::format("IIG {}", k) : "IIG (integral image)");
        rows.push_back(pairs > 1 ? fmt::format("FHG {}", k) : "FHG (determinants)");
    }
    rows.push_back("PLB2 (their DMA)");
    rows.push_back("CPU (descriptors)");
    std::string body;
    for (size_t i = 0; i < rows.size(); ++i)
        body += fmt::format("<text x=\"0\" y=\"{:.1f}\">{}</text>", row_y(i) + 17, xml_escape(rows[i]));
    auto bar = [&](size_t row, size_t frame, double from, double to, const std::string& what) {
        const double x0 = at_x(from, x), x1 = at_x(to, x), y = row_y(row) + 3;
        body += fmt::format(
            "<rect class=\"task\" data-frame=\"{}\" data-start-ms=\"{:.3f}\" data-end-ms=\"{:.3f}\" x=\"{:.1f}\" "
            "y=\"{:.1f}\" width=\"{:.1f}\" height=\"20\" fill=\"{}\"><title>frame {}: {} {:.2f} to {:.2f} "
            "ms</title></rect>",
            frame, from, to, x0, y, std::max(1.0, x1 - x0), colour(frame), frame, what, from, to);
        if (x1 - x0 > 24)
            body += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"white\">{}</text>", x0 + 4, y + 15, frame);
    };
    for (size_t i = 0; i < shown; ++i) {
        const Json& f = frames[i];
        const size_t k = i % pairs;
        const double start = f["start_ms"], integral = f["integral_done_ms"], determinants = f["determinants_done_ms"];
        bar(2 * k, i, start, integral, "integral image");
        bar(2 * k + 1, i, start, determinants, "determinants");
        bar(rows.size() - 1, i, determinants, f["done_ms"], "descriptors");
    }
    // PLB2's busier direction per bin, in five shades of its share. A long run's series have
    // widened their bins, each at its own time: each is read at the finer one's bins.
    const Json& plb2 = r["buses"]["plb2"];
    const Json &read = plb2["read"]["busy_series"], &write = plb2["write"]["busy_series"];
    auto share_at = [](const Json& series, double t_ms) {
        const size_t b = size_t(t_ms / (series["bin_s"].get<double>() * 1e3));
        return b < series["values"].size() ? series["values"][b].get<double>() : 0.0;
    };
    const char* const shades[] = {"#dbe4ee", "#a9bdd4", "#7694b8", "#46699a", "#1b3a5c"};
    const double bin_ms = std::min(read["bin_s"].get<double>(), write["bin_s"].get<double>()) * 1e3;
    const double y = row_y(rows.size() - 2) + 3;
    for (size_t b = 0; b * bin_ms < end_ms; ++b) {
        const double mid = (b + 0.5) * bin_ms, share = std::max(share_at(read, mid), share_at(write, mid));
        if (share <= 0) continue;
        const size_t shade = std::min<size_t>(4, size_t(share * 5));
        body += fmt::format(
            "<rect class=\"bus\" data-share=\"{:.4f}\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"20\" "
            "fill=\"{}\"><title>PLB2 {:.1f} % busy</title></rect>",
            share, at_x(b * bin_ms, x), y, at_x(std::min(end_ms, (b + 1) * bin_ms), x) - at_x(b * bin_ms, x),
            shades[shade], 100 * share);
    }
    const double axis_y = row_y(rows.size()) + 4;
    body += x_axis(x, axis_y, "ms");
    std::vector<Key> keys;
    for (size_t i = 0; i < shown; ++i) keys.push_back({colour(i), fmt::format("frame {}", i)});
    for (size_t s = 0; s < 5; ++s) keys.push_back({shades[s], fmt::format("PLB2 {}-{} % busy", 20 * s, 20 * (s + 1))});
    double bottom = 0;
    const std::string keys_svg = legend(keys, axis_y + 40, bottom);
    return svg_open("gantt", bottom, fmt::format("The first {} frames across the chip", shown)) + body + keys_svg +
           "</svg>";
}

std::string resource_chart(const Json& table) {
    double period = 0;
    for (const auto& [name, row] : table.items()) period = std::max(period, row["period_ms"].get<double>());
    if (period <= 0) return "";
    const Ticks x = round_ticks(0, period, 8);
    std::vector<std::string> causes;  // every wait cause, a colour each
    for (const auto& [name, row] : table.items())
        for (const auto& [cause, ms] : row["waits_ms"].items())
            if (std::find(causes.begin(), causes.end(), cause) == causes.end()) causes.push_back(cause);
    const char* const wait_colours[] = {"#f28e2b", "#e15759", "#edc948", "#b07aa1", "#9c755f",
                                        "#76b7b2", "#ff9da7", "#59a14f", "#d37295", "#86bcb6"};
    auto wait_colour = [&](const std::string& cause) {
        return wait_colours[size_t(std::find(causes.begin(), causes.end(), cause) - causes.begin()) % 10];
    };
    std::string body;
    size_t i = 0;
    for (const auto& item : table.items()) {
        const std::string& name = item.key();  // a local the lambda below may capture (a binding may not)
        const Json& row = item.value();
        const double y = row_y(i++);
        body += fmt::format("<text x=\"0\" y=\"{:.1f}\">{} ({:.1f} % busy)</text>", y + 17, xml_escape(name),
                            100 * row["busy_share"].get<double>());
        double at = 0;
        auto piece = [&](double ms, const std::string& fill, const std::string& what) {
            // A CPU waits while it is busy elsewhere in the frame (its sum can pass the period): clipped.
            if (ms <= 0 || at >= period) return;
            const double x0 = at_x(at, x), x1 = at_x(std::min(period, at + ms), x);
            body += fmt::format(
                "<rect class=\"{}\" data-resource=\"{}\" data-ms=\"{:.3f}\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" "
                "height=\"20\" fill=\"{}\"><title>{}: {} {:.2f} ms</title></rect>",
                what == "busy" || what == "idle" ? what : "wait", xml_escape(name), ms, x0, y + 3,
                std::max(0.5, x1 - x0), fill, xml_escape(name), xml_escape(what), ms);
            at += ms;
        };
        piece(row["busy_ms"], "#4e79a7", "busy");
        for (const auto& [cause, ms] : row["waits_ms"].items()) piece(ms, wait_colour(cause), "waiting: " + cause);
        piece(row["idle_ms"], "#cccccc", "idle");
    }
    const double axis_y = row_y(table.size()) + 4;
    body += x_axis(x, axis_y, "ms");
    std::vector<Key> keys{{"#4e79a7", "busy"}};
    for (const std::string& c : causes) keys.push_back({wait_colour(c), "waiting: " + c});
    keys.push_back({"#cccccc", "idle"});
    double bottom = 0;
    const std::string keys_svg = legend(keys, axis_y + 40, bottom);
    return svg_open("resources", bottom,
                    fmt::format("Where each resource's frame goes (one steady-state period: {:.2f} ms)", period)) +
           body + keys_svg + "</svg>";
}

namespace {

struct Line {
    std::string name;
    const Json* series;  // {"bin_s", "values"}
};

// Figures per time bin as step lines over the run, on a y axis of round ticks up to the
// largest; `percent`: the values are shares, shown in %.
std::string line_chart(const std::string& id, const std::string& title, const std::vector<Line>& lines, bool percent,
                       const std::string& y_unit, double end_ms) {
    if (end_ms <= 0 || lines.empty()) return "";
    double peak = 0;
    for (const Line& l : lines)
        for (const auto& v : (*l.series)["values"]) peak = std::max(peak, v.get<double>());
    const double scale = percent ? 100 : 1;
    const Ticks y = round_ticks(0, std::max(peak * scale, 1.0), 4);
    const Ticks x = round_ticks(0, end_ms, 8);
    const double top = 30, plot_h = 160;
    auto py = [&](double v) { return top + plot_h * (1 - std::min(1.0, v * scale / y.hi())); };
    std::string body;
    for (const double t : y.at)
        body += fmt::format(
            "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#e4e4e4\"/><text class=\"tick\" "
            "x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5} {6}</text>",
            kLeft, py(t / scale), kWidth - kRight, kLeft - 6, py(t / scale) + 4, tick_label(t, y.step),
            xml_escape(percent ? "%" : y_unit));
    std::vector<Key> keys;
    size_t i = 0;
    for (const Line& l : lines) {
        const double bin_ms = (*l.series)["bin_s"].get<double>() * 1e3;
        std::string points;
        double line_peak = 0;
        size_t b = 0;
        for (const auto& v : (*l.series)["values"]) {
            const double yv = py(v.get<double>());
            points +=
                fmt::format("{:.1f},{:.1f} {:.1f},{:.1f} ", at_x(b * bin_ms, x), yv, at_x((b + 1) * bin_ms, x), yv);
            line_peak = std::max(line_peak, v.get<double>());
            ++b;
        }
        body += fmt::format(
            "<polyline class=\"series\" data-name=\"{}\" data-peak=\"{:g}\" data-bins=\"{}\" points=\"{}\" "
            "fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>",
            xml_escape(l.name), line_peak, b, points, colour(i));
        keys.push_back(
            {colour(i++), fmt::format("{} (peak {:g}{})", l.name, line_peak * scale, percent ? " %" : " " + y_unit)});
    }
    body +=
        fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"#333\"/>", kLeft, top, top + plot_h);
    body += x_axis(x, top + plot_h, "ms");
    double bottom = 0;
    const std::string keys_svg = legend(keys, top + plot_h + 44, bottom);
    return svg_open(id, bottom, title) + body + keys_svg + "</svg>";
}

}  // namespace

std::string bus_chart(const Json& r) {
    std::vector<Line> lines;
    for (const auto& [bus, b] : r["buses"].items())
        for (const char* path : {"read", "write"})
            if (b[path].contains("busy_series") && b[path]["bytes"].get<double>() > 0)
                lines.push_back({bus + " " + path, &b[path]["busy_series"]});
    if (r.contains("memory") && r["memory"].contains("busy_series"))
        lines.push_back({"DDR", &r["memory"]["busy_series"]});
    return line_chart("buses", "Bus and DDR utilisation over the run (busy share per time bin)", lines, true, "",
                      r["sim_time_s"].get<double>() * 1e3);
}

std::string fifo_charts(const Json& r) {
    if (!r.contains("fhg")) return "";
    const Json& fhg = r["fhg"].is_array() ? r["fhg"][0] : r["fhg"];
    if (!fhg.contains("line_fifo_series")) return "";
    const double end_ms = r["sim_time_s"].get<double>() * 1e3;
    return line_chart("line_fifo", "The FHG's line FIFO over the run (integral lines held, highest per time bin)",
                      {{"line FIFO", &fhg["line_fifo_series"]}}, false, "lines", end_ms) +
           line_chart("maxima_fifo",
                      "The FHG's maxima FIFO over the run (candidates waiting for the CPU, highest per time bin)",
                      {{"maxima FIFO", &fhg["maxima_fifo_series"]}}, false, "entries", end_ms);
}

std::string distribution_chart(const Json& v) {
    if (!v.contains("doubt") || !v["doubt"].contains("fps")) return "";
    const Json& d = v["doubt"]["fps"];
    const double budget = v.value("budget_fps", 0.0), at_defaults = v.value("fps", 0.0);
    const Ticks x = round_ticks(0, std::max({d["max"].get<double>(), budget, at_defaults}) * 1.02, 8);
    const double y = 44, h = 26;
    std::string body = fmt::format(
        "<text x=\"0\" y=\"{0:.1f}\">over the unknowns jointly</text>"
        "<line x1=\"{1:.1f}\" y1=\"{2:.1f}\" x2=\"{3:.1f}\" y2=\"{2:.1f}\" stroke=\"#333\"/>"
        "<rect class=\"band\" data-p5=\"{4:g}\" data-p95=\"{5:g}\" x=\"{6:.1f}\" y=\"{7:.1f}\" width=\"{8:.1f}\" "
        "height=\"{9}\" fill=\"#a9bdd4\" stroke=\"#333\"/>"
        "<line class=\"median\" data-p50=\"{10:g}\" x1=\"{11:.1f}\" y1=\"{7:.1f}\" x2=\"{11:.1f}\" y2=\"{12:.1f}\" "
        "stroke=\"#1b3a5c\" stroke-width=\"3\"/>",
        y + 17, at_x(d["min"], x), y + h / 2, at_x(d["max"], x), d["p5"].get<double>(), d["p95"].get<double>(),
        at_x(d["p5"], x), y, at_x(d["p95"], x) - at_x(d["p5"], x), h, d["p50"].get<double>(), at_x(d["p50"], x), y + h);
    if (budget > 0)
        body += fmt::format(
            "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#c00\" stroke-width=\"2\" "
            "stroke-dasharray=\"6 4\"/>",
            at_x(budget, x), y - 14, y + h + 6);
    body += fmt::format("<path d=\"M{0:.1f},{1:.1f}l-6,-10h12z\" fill=\"#333\"/>", at_x(at_defaults, x), y - 2);
    body += x_axis(x, y + h + 12, "frames/s");
    double bottom = 0;
    const std::string keys_svg = legend({{"#a9bdd4", "5th to 95th percentile (line: least to most)"},
                                         {"#1b3a5c", fmt::format("median {:.2f}", d["p50"].get<double>())},
                                         {"#c00", fmt::format("budget {:g}", budget)},
                                         {"#333", fmt::format("at the defaults {:.2f}", at_defaults)}},
                                        y + h + 52, bottom);
    return svg_open("distribution", bottom,
                    fmt::format("Frames/s over the unknowns jointly ({} points): met with probability {:.0f} %",
                                v["doubt"].value("points", 0), 100 * v["doubt"].value("probability_met", 0.0))) +
           body + keys_svg + "</svg>";
}

std::string cost_chart(const Json& r) {
    if (!r.contains("fpga_resources") || !r.contains("power")) return "";
    const Json &f = r["fpga_resources"], &p = r["power"];
    std::vector<std::pair<std::string, double>> bars;
    for (const auto& [kind, share] : f["share"].items()) bars.emplace_back(kind, share.get<double>());
    const double watts = p["watts"].get<double>(), budget_w = p.value("budget_w", 0.0);
    bars.emplace_back("power", budget_w > 0 ? watts / budget_w : 0);
    const Ticks x = round_ticks(
        0,
        std::max(100.0,
                 100 * std::max_element(bars.begin(), bars.end(), [](auto& a, auto& b) { return a.second < b.second; })
                           ->second),
        5);
    std::string body;
    for (size_t i = 0; i < bars.size(); ++i) {
        const auto& [name, share] = bars[i];
        const double y = row_y(i);
        static const std::vector<std::pair<std::string, std::string>> names = {
            {"ramb36", "RAMB36"}, {"dsp48e", "DSP48E"}, {"luts", "LUTs"}, {"ffs", "flip-flops"}};
        std::string shown = name;
        for (const auto& [key, text] : names)
            if (key == name) shown = text;
        const std::string label = name == "power" ? fmt::format("power: {:.2f} W of {:g} W", watts, budget_w)
                                                  : fmt::format("{}: {:g} of {:g}", shown, f["total"].value(name, 0.0),
                                                                f["capacity"].value(name, 0.0));
        body += fmt::format(
            "<text x=\"0\" y=\"{:.1f}\">{}</text><rect class=\"cost\" data-name=\"{}\" data-share=\"{:.4f}\" "
            "x=\"{}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"20\" fill=\"{}\"/>",
            y + 17, xml_escape(label), xml_escape(name), share, kLeft, y + 3, at_x(100 * share, x) - kLeft,
            share > 1         ? "#e15759"
            : name == "power" ? "#f28e2b"
                              : "#4e79a7");
    }
    const double axis_y = row_y(bars.size()) + 4;
    body += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"30\" x2=\"{0:.1f}\" y2=\"{1}\" stroke=\"#c00\" stroke-dasharray=\"6 4\"/>",
        at_x(100, x), axis_y);
    body += x_axis(x, axis_y, "%");
    double bottom = 0;
    const std::string keys_svg = legend({{"#4e79a7", "share of the device's resource"},
                                         {"#f28e2b", "share of the power budget"},
                                         {"#e15759", "over the device or the budget"},
                                         {"#c00", "100 %: the whole device, the whole budget"}},
                                        axis_y + 40, bottom);
    return svg_open(
               "costs", bottom,
               fmt::format("The configuration against the {} and the power budget", f["device"].get<std::string>())) +
           body + keys_svg + "</svg>";
}

}  // namespace surfvp
