#include "platform/verdict/tornado.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace surfvp {
namespace {

constexpr double kLabel = 330, kChart = 420, kRow = 24, kTop = 58, kRight = 30;

std::string escape(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else
            out += c;
    }
    return out;
}

}  // namespace

std::string tornado_svg(const nlohmann::ordered_json& band, double budget, size_t rows) {
    const double ref = band["run_fps"].get<double>();
    std::vector<const nlohmann::ordered_json*> shown;
    for (const auto& axis : band["axes"])
        if (shown.size() < rows && axis["effect_fps"].get<double>() > 0) shown.push_back(&axis);
    double lo = std::min(band["low_fps"].get<double>(), ref), hi = std::max(band["high_fps"].get<double>(), ref);
    if (budget > 0) lo = std::min(lo, budget), hi = std::max(hi, budget);
    const double pad = std::max(0.12 * (hi - lo), 0.2);  // room for the value labels beside the bars
    lo = std::max(0.0, lo - pad);
    hi += pad;
    auto x = [&](double fps) { return kLabel + (fps - lo) / (hi - lo) * kChart; };
    const double height = kTop + kRow * double(std::max<size_t>(shown.size(), 1)) + 40;
    const double width = kLabel + kChart + kRight;

    std::string svg = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0:.0f}\" height=\"{1:.0f}\" viewBox=\"0 0 {0:.0f} "
        "{1:.0f}\" "
        "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
        width, height);
    svg +=
        "<text x=\"10\" y=\"20\" font-size=\"15\" font-weight=\"bold\">Frames/s under each unknown about the chip at "
        "its low "
        "and its high</text>\n";
    svg += fmt::format(
        "<rect x=\"10\" y=\"30\" width=\"12\" height=\"10\" fill=\"#4e79a7\"/><text x=\"27\" y=\"39\">low</text>"
        "<rect x=\"65\" y=\"30\" width=\"12\" height=\"10\" fill=\"#f28e2b\"/><text x=\"82\" y=\"39\">high</text>"
        "<text x=\"125\" y=\"39\">the run: {:.2f}; a bar: the run's rate plus the change's effect in "
        "{}-frame runs</text>\n",
        ref, band["frames"].get<unsigned>());
    for (size_t i = 0; i < shown.size(); ++i) {
        const auto& a = *shown[i];
        const double y = kTop + kRow * double(i);
        svg += fmt::format("<text x=\"{:.0f}\" y=\"{:.1f}\" text-anchor=\"end\">{} ({} / {})</text>\n", kLabel - 8,
                           y + 15, escape(a["parameter"].get<std::string>()),
                           escape(a["low"]["value"].get<std::string>()), escape(a["high"]["value"].get<std::string>()));
        for (const char* side : {"low", "high"}) {
            const auto& s = a[side];
            if (!s.contains("fps") || s["fps"].is_null()) continue;
            const double fps = s["fps"].get<double>();
            const double x0 = x(std::min(fps, ref)), x1 = x(std::max(fps, ref));
            svg += fmt::format(
                "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"16\" fill=\"{}\"><title>{} = {}: "
                "{:.3f} frames/s</title></rect>\n",
                x0, y + 3, std::max(x1 - x0, 1.0), std::string(side) == "low" ? "#4e79a7" : "#f28e2b",
                escape(a["parameter"].get<std::string>()), escape(s["value"].get<std::string>()), fps);
            if (std::abs(fps - ref) < 0.005) continue;  // no visible bar: no label to crowd the others
            const bool left = fps < ref;
            svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\" text-anchor=\"{}\">{:.2f}</text>\n",
                               left ? x0 - 3 : x1 + 3, y + 15, left ? "end" : "start", fps);
        }
    }
    const double bottom = kTop + kRow * double(std::max<size_t>(shown.size(), 1));
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1:.0f}\" x2=\"{0:.1f}\" y2=\"{2:.0f}\" stroke=\"#333\" stroke-width=\"1.5\"/>\n",
        x(ref), kTop - 4, bottom);
    if (budget > 0)
        svg += fmt::format(
            "<line x1=\"{0:.1f}\" y1=\"{1:.0f}\" x2=\"{0:.1f}\" y2=\"{2:.0f}\" stroke=\"#c00\" stroke-width=\"1.5\" "
            "stroke-dasharray=\"5,3\"/><text x=\"{0:.1f}\" y=\"{3:.0f}\" fill=\"#c00\" text-anchor=\"middle\">"
            "budget {4:g}</text>\n",
            x(budget), kTop - 4, bottom, bottom + 28, budget);
    // The axis: ticks at round frame rates.
    const double span = hi - lo, tick = span > 8 ? 2 : span > 4 ? 1 : span > 2 ? 0.5 : 0.25;
    svg += fmt::format("<line x1=\"{:.0f}\" y1=\"{:.0f}\" x2=\"{:.0f}\" y2=\"{:.0f}\" stroke=\"#999\"/>\n", kLabel,
                       bottom + 2, kLabel + kChart, bottom + 2);
    for (double t = std::ceil(lo / tick) * tick; t <= hi; t += tick)
        svg += fmt::format(
            "<text x=\"{:.1f}\" y=\"{:.0f}\" font-size=\"10\" text-anchor=\"middle\" fill=\"#555\">{:g}</text>\n", x(t),
            bottom + 14, t);
    svg += "</svg>\n";
    return svg;
}

}  // namespace surfvp
