#include "platform/sweep/sweep_plots.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "models/host/xml_text.h"
#include "platform/report/chart_ticks.h"
#include "platform/sweep/sweep_plan.h"

namespace surfvp {
namespace {

// A frames/s chart: its frame, y ticks, x ticks the caller places, the budget dashed. Every
// text it is given (the sweep's name, axis keys, values, point ids) is escaped here: a value
// may hold '<', '&' or quotes, and the plot must stay well-formed SVG.
class FpsChart {
public:
    static constexpr double W = 640, H = 400, L = 64, R = 16, T = 36, B = 48;

    FpsChart(const std::string& title, const std::string& x_label, double x0, double x1,
             const std::vector<SweepRow>& rows)
        : x0_(x0), x1_(x1 > x0 ? x1 : x0 + 1) {
        double budget = 0;
        for (const SweepRow& r : rows) {
            y1_ = std::max(y1_, r.figures.value("fps", 0.0));
            budget = std::max(budget, r.figures.value("budget_fps", 0.0));
        }
        y_ = round_ticks(0, std::max(y1_, budget) * 1.05 + 1e-9);
        y1_ = y_.hi();
        svg_ = fmt::format(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" font-family=\"sans-serif\" "
            "font-size=\"12\"><rect width=\"100%\" height=\"100%\" fill=\"white\"/>"
            "<text x=\"{2}\" y=\"20\" font-size=\"14\">{3}</text>"
            "<line x1=\"{2}\" y1=\"{4}\" x2=\"{5}\" y2=\"{4}\" stroke=\"black\"/>"
            "<line x1=\"{2}\" y1=\"{6}\" x2=\"{2}\" y2=\"{4}\" stroke=\"black\"/>"
            "<text x=\"{7}\" y=\"{8}\" text-anchor=\"middle\">{9}</text>"
            "<text x=\"14\" y=\"{10}\" transform=\"rotate(-90 14 {10})\" text-anchor=\"middle\">frames/s</text>",
            W, H, L, xml_escape(title), H - B, W - R, T, (L + W - R) / 2, H - 10, xml_escape(x_label), (T + H - B) / 2);
        for (const double y : y_.at)
            svg_ += fmt::format(
                "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#eee\"/>"
                "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>",
                L, py(y), W - R, L - 6, py(y) + 4, tick_label(y, y_.step));
        if (budget > 0)
            svg_ += fmt::format(
                "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#c00\" stroke-dasharray=\"6 4\"/>"
                "<text x=\"{2}\" y=\"{3:.1f}\" text-anchor=\"end\" fill=\"#c00\">budget {4:g} frames/s</text>",
                L, py(budget), W - R, py(budget) - 4, budget);
    }
    double px(double x) const { return L + (x - x0_) / (x1_ - x0_) * (W - L - R); }
    double py(double y) const { return H - B - y / y1_ * (H - T - B); }
    void x_tick(double x, const std::string& label) {
        svg_ += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>", px(x), H - B + 16,
                            xml_escape(label));
    }
    void line(const std::vector<std::pair<double, double>>& points, const std::string& stroke,
              const std::string& title) {
        std::string p;
        for (const auto& [x, y] : points) p += fmt::format("{:.1f},{:.1f} ", px(x), py(y));
        svg_ += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\"><title>{}</title></polyline>", p,
                            stroke, xml_escape(title));
    }
    void label(double x, double y, const std::string& text) {
        svg_ +=
            fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\" font-size=\"10\" fill=\"#466\">{}</text>",
                        px(x) - 8, py(y) - 6, xml_escape(text));
    }
    // Where the limit moves between two neighbouring points of a line: a dotted rule between
    // them and the two limits' names.
    void limit_moves(double x, const std::string& from, const std::string& to) {
        svg_ += fmt::format(
            "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#b60\" stroke-dasharray=\"2 3\"/>"
            "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\" font-size=\"10\" fill=\"#b60\">limit {4} → "
            "{5}</text>",
            px(x), T, H - B, T + 10 + 12 * (marks_++ % 3), xml_escape(from), xml_escape(to));
    }
    // A point that does not fit the device: drawn apart (a grey cross), never on the front.
    void misfit(double x, const SweepRow& r) {
        const double fps = r.figures.value("fps", 0.0), cx = px(x), cy = py(fps);
        svg_ += fmt::format(
            "<path d=\"M{0:.1f},{1:.1f}l8,8m0,-8l-8,8\" stroke=\"#999\" stroke-width=\"2\"><title>{2}: {3:.3g} "
            "frames/s, does not fit the device</title></path>",
            cx - 4, cy - 4, xml_escape(r.id), fps);
        misfits_ = true;
    }
    // A point of the sweep; filled when it is on the Pareto front.
    void point(double x, const SweepRow& r, bool on_front) {
        const double fps = r.figures.value("fps", 0.0);
        svg_ += fmt::format(
            "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" stroke=\"#1b3a5c\" fill=\"{}\"><title>{}: {:.3g} frames/s{}"
            "</title></circle>",
            px(x), py(fps), on_front ? "#1b3a5c" : "white", xml_escape(r.id), fps, on_front ? " (Pareto front)" : "");
    }
    std::string finish() {
        return svg_ + fmt::format("<text x=\"{}\" y=\"{}\" fill=\"#1b3a5c\">filled: on the Pareto front{}</text></svg>",
                                  L + 8, H - B - 8, misfits_ ? "; grey cross: does not fit the device" : "");
    }

private:
    double x0_, x1_, y1_ = 0;
    Ticks y_;
    int marks_ = 0;
    bool misfits_ = false;
    std::string svg_;
};

bool fits(const SweepRow& r) { return !r.figures.contains("fits") || r.figures["fits"] != false; }

// The points that ran, the front on top of a point of equal figures; those that do not fit
// the device apart.
template <typename X>
void draw_points(FpsChart& chart, const std::vector<SweepRow>& rows, const std::vector<bool>& front, X&& x_of) {
    for (size_t i = 0; i < rows.size(); ++i)
        if (rows[i].error.empty() && !fits(rows[i])) chart.misfit(x_of(rows[i]), rows[i]);
    for (bool on_front : {false, true})
        for (size_t i = 0; i < rows.size(); ++i)
            if (rows[i].error.empty() && fits(rows[i]) && front[i] == on_front)
                chart.point(x_of(rows[i]), rows[i], front[i]);
}

std::optional<double> number_in(const std::string& value) {
    const auto q = split_quantity(value);
    return q ? std::optional<double>(q->first) : std::nullopt;
}

}  // namespace

std::string axis_plot(const std::string& name, const std::string& axis, const std::vector<std::string>& axes,
                      const std::vector<SweepRow>& rows, const std::vector<bool>& front) {
    std::vector<std::string> categories;  // the axis's values in first-seen order
    bool numeric = true;
    for (const SweepRow& r : rows) {
        const std::string v = r.params.value(axis, "");
        if (std::find(categories.begin(), categories.end(), v) == categories.end()) categories.push_back(v);
        numeric = numeric && number_in(v).has_value();
    }
    auto x_of = [&](const std::string& v) {
        return numeric ? *number_in(v)
                       : double(std::find(categories.begin(), categories.end(), v) - categories.begin());
    };
    double x0 = 1e300, x1 = -1e300;
    for (const std::string& c : categories) x0 = std::min(x0, x_of(c)), x1 = std::max(x1, x_of(c));
    const auto unit = categories.empty() ? std::nullopt : split_quantity(categories[0]);
    FpsChart chart(fmt::format("{}: frames/s against {}", name, axis),
                   axis + (unit && !unit->second.empty() ? " (" + unit->second + ")" : ""), x0, x1, rows);
    std::set<double> ticks;
    for (const std::string& c : categories) ticks.insert(x_of(c));
    for (double t : ticks) chart.x_tick(t, numeric ? fmt::format("{:.6g}", t) : categories[size_t(t)]);
    // One line per combination of the other axes' values, each point with its limit.
    std::map<std::string, std::vector<std::tuple<double, double, std::string>>> lines;
    for (const SweepRow& r : rows) {
        if (!r.error.empty()) continue;
        std::string others;
        for (const std::string& a : axes)
            if (a != axis) others += a + "=" + r.params.value(a, "") + " ";
        lines[others].emplace_back(x_of(r.params.value(axis, "")), r.figures.value("fps", 0.0),
                                   r.figures.value("bottleneck", ""));
    }
    std::set<double> marked;       // where a limit move is drawn: once per place
    std::vector<double> labelled;  // the heights of the line labels so far: one that would overlap is left out
    for (auto& [others, limited] : lines) {
        std::sort(limited.begin(), limited.end());
        std::vector<std::pair<double, double>> pts;
        for (size_t i = 0; i < limited.size(); ++i) {
            const auto& [x, y, limit] = limited[i];
            pts.emplace_back(x, y);
            if (i == 0) continue;
            const auto& [x_before, y_before, limit_before] = limited[i - 1];
            const double mid = (x + x_before) / 2;
            if (limit != limit_before && !limit.empty() && !limit_before.empty() && marked.insert(mid).second)
                chart.limit_moves(mid, limit_before, limit);
        }
        chart.line(pts, "#8aa", others);
        const double end_y = chart.py(pts.back().second);
        if (others.empty() ||
            std::any_of(labelled.begin(), labelled.end(), [&](double y) { return std::abs(y - end_y) < 12; }))
            continue;
        labelled.push_back(end_y);
        chart.label(pts.back().first, pts.back().second, others);
    }
    draw_points(chart, rows, front, [&](const SweepRow& r) { return x_of(r.params.value(axis, "")); });
    return chart.finish();
}

std::string front_plot(const std::string& name, const std::string& cost, const std::vector<SweepRow>& rows,
                       const std::vector<bool>& front) {
    double x0 = 1e300, x1 = -1e300;
    for (const SweepRow& r : rows)
        if (r.error.empty())
            x0 = std::min(x0, r.figures.value(cost, 0.0)), x1 = std::max(x1, r.figures.value(cost, 0.0));
    if (x0 > x1) x0 = 0, x1 = 1;
    const Ticks ticks = round_ticks(x0, x1, 4);
    FpsChart chart(fmt::format("{}: frames/s against {} (line: the most frames/s for it)", name, cost), cost,
                   ticks.lo(), ticks.hi(), rows);
    for (const double x : ticks.at) chart.x_tick(x, tick_label(x, ticks.step));
    // The most frames/s any point gives for at most each cost: a staircase from the cheapest up.
    std::vector<std::pair<double, double>> all, stairs;
    for (const SweepRow& r : rows)
        if (r.error.empty() && fits(r)) all.push_back({r.figures.value(cost, 0.0), r.figures.value("fps", 0.0)});
    std::sort(all.begin(), all.end());
    for (const auto& [x, y] : all)
        if (stairs.empty() || y > stairs.back().second) {
            if (!stairs.empty()) stairs.push_back({x, stairs.back().second});
            stairs.push_back({x, y});
        }
    if (!stairs.empty()) chart.line(stairs, "#1b3a5c", fmt::format("the most frames/s for the {}", cost));
    draw_points(chart, rows, front, [&](const SweepRow& r) { return r.figures.value(cost, 0.0); });
    return chart.finish();
}

}  // namespace surfvp
