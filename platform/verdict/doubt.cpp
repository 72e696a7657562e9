#include "platform/verdict/doubt.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <numeric>
#include <random>

#include "platform/scenario/parameters.h"

namespace surfvp {
namespace {
using Json = nlohmann::ordered_json;

constexpr size_t kSobolSamples = 4096;  // base samples of the surrogate (N (k + 2) evaluations)

// Widths and choices take their listed values; the rest any value of their range.
bool discrete(const ParamSpec& p) {
    return p.kind == ParamKind::choice || p.kind == ParamKind::text || p.kind == ParamKind::bits ||
           p.kind == ParamKind::bytes || p.kind == ParamKind::address;
}

bool same(const ParamSpec& p, const std::string& a, const std::string& b) {
    return discrete(p) && p.kind != ParamKind::bits && p.kind != ParamKind::bytes
               ? a == b
               : parse_value(p, a) == parse_value(p, b);
}

std::string value_text(const Unknown& u, double unit) {
    if (!u.continuous()) return u.values[std::min(u.values.size() - 1, size_t(unit * double(u.values.size())))];
    const ParamSpec& p = *u.spec;
    const double v = u.low + unit * (u.high - u.low);
    if (p.kind == ParamKind::frequency) return fmt::format("{} MHz", std::round(v / 1e3) / 1e3);
    if (p.kind == ParamKind::real) return format_value(p, v);
    return format_value(p, std::round(v));
}

// The surrogate's inputs: a continuous unknown its coordinate, a discrete one an indicator of
// each value but the first.
size_t feature_count(const std::vector<Unknown>& unknowns) {
    size_t n = 1;  // the intercept
    for (const Unknown& u : unknowns) n += u.continuous() ? 1 : u.values.size() - 1;
    return n;
}

using RowRef = Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;

void features(const std::vector<Unknown>& unknowns, const std::vector<double>& unit, RowRef row) {
    Eigen::Index f = 0;
    row(f++) = 1;
    for (size_t k = 0; k < unknowns.size(); ++k) {
        const Unknown& u = unknowns[k];
        if (u.continuous()) {
            row(f++) = unit[k];
            continue;
        }
        const size_t chosen = std::min(u.values.size() - 1, size_t(unit[k] * double(u.values.size())));
        for (size_t v = 1; v < u.values.size(); ++v) row(f++) = chosen == v ? 1 : 0;
    }
}

double percentile(std::vector<double> sorted, double p) {
    std::sort(sorted.begin(), sorted.end());
    const double at = p * double(sorted.size() - 1);
    const size_t below = size_t(std::floor(at));
    const size_t above = std::min(sorted.size() - 1, below + 1);
    return sorted[below] + (at - double(below)) * (sorted[above] - sorted[below]);
}

// Per resource, log(alone frames/s) linear in the features; the rate is the least of them
// times `kappa`, the points' median of their rate over that least.
struct Surrogate {
    std::vector<Eigen::VectorXd> beta;
    double kappa = 1;
    double fps(const Eigen::RowVectorXd& x) const {
        double least = INFINITY;
        for (const Eigen::VectorXd& b : beta) least = std::min(least, std::exp(x.dot(b)));
        return kappa * least;
    }
};

Surrogate fit(const Eigen::MatrixXd& x, const std::map<std::string, Eigen::VectorXd>& log_alone,
              const Eigen::VectorXd& fps) {
    Surrogate s;
    // A small ridge keeps a feature that never moves a resource from making the system singular.
    const Eigen::MatrixXd gram = x.transpose() * x + 1e-6 * Eigen::MatrixXd::Identity(x.cols(), x.cols());
    const Eigen::LDLT<Eigen::MatrixXd> solver(gram);
    for (const auto& [resource, y] : log_alone) s.beta.push_back(solver.solve(x.transpose() * y));
    std::vector<double> ratios;
    for (Eigen::Index i = 0; i < x.rows(); ++i) ratios.push_back(fps(i) / s.fps(x.row(i)));
    s.kappa = percentile(ratios, 0.5);
    return s;
}

// First-order and total indices of the surrogate (Saltelli's and Jansen's estimators).
Json sensitivity(const std::vector<Unknown>& unknowns, const Surrogate& s, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(0, 1);
    const size_t k = unknowns.size(), n = kSobolSamples;
    std::vector<std::vector<double>> a(n, std::vector<double>(k)), b = a;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j < k; ++j) a[i][j] = uniform(rng), b[i][j] = uniform(rng);
    Eigen::RowVectorXd row(Eigen::Index(feature_count(unknowns)));
    auto eval = [&](const std::vector<double>& unit) {
        features(unknowns, unit, row);
        return s.fps(row);
    };
    std::vector<double> fa(n), fb(n);
    for (size_t i = 0; i < n; ++i) fa[i] = eval(a[i]), fb[i] = eval(b[i]);
    std::vector<double> both = fa;
    both.insert(both.end(), fb.begin(), fb.end());
    const double mean = std::accumulate(both.begin(), both.end(), 0.0) / double(both.size());
    double var = 0;
    for (double v : both) var += (v - mean) * (v - mean);
    var /= double(both.size());
    Json rows = Json::array();
    for (size_t j = 0; j < k; ++j) {
        double first = 0, total = 0;
        for (size_t i = 0; i < n; ++i) {
            std::vector<double> mixed = a[i];
            mixed[j] = b[i][j];
            const double fab = eval(mixed);
            first += fb[i] * (fab - fa[i]);
            total += (fa[i] - fab) * (fa[i] - fab);
        }
        const double s1 = var > 0 ? first / double(n) / var : 0, st = var > 0 ? total / (2.0 * double(n)) / var : 0;
        rows.push_back(
            {{"parameter", unknowns[j].spec->key}, {"first_order", std::max(0.0, s1)}, {"total", std::max(0.0, st)}});
    }
    std::stable_sort(rows.begin(), rows.end(),
                     [](const Json& x, const Json& y) { return x["total"].get<double>() > y["total"].get<double>(); });
    return rows;
}

}  // namespace

std::vector<Unknown> unknowns_of(const std::vector<const ParamSpec*>& banded, const Config& config) {
    std::vector<Unknown> out;
    for (const ParamSpec* p : banded) {
        if (p->role != ParamRole::unknown) continue;
        const std::string& now = config.value(p->key);
        if (same(*p, p->band.low, now) && same(*p, p->band.high, now)) continue;  // nothing to vary
        Unknown u{p, {}, 0, 0};
        if (discrete(*p)) {
            for (const std::string& v : {p->band.low, now, p->band.high})
                if (std::none_of(u.values.begin(), u.values.end(),
                                 [&](const std::string& w) { return same(*p, v, w); }))
                    u.values.push_back(v);
        } else {
            const double lo = parse_value(*p, p->band.low), hi = parse_value(*p, p->band.high),
                         at = parse_value(*p, now);
            u.low = std::min({lo, hi, at});
            u.high = std::max({lo, hi, at});
        }
        out.push_back(u);
    }
    return out;
}

JointDesign joint_design(const std::vector<Unknown>& unknowns, size_t points, uint32_t seed) {
    JointDesign d;
    d.unit.assign(points, std::vector<double>(unknowns.size()));
    d.sets.assign(points, {});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(0, 1);
    for (size_t k = 0; k < unknowns.size(); ++k) {
        std::vector<size_t> strata(points);
        std::iota(strata.begin(), strata.end(), size_t(0));
        std::shuffle(strata.begin(), strata.end(), rng);
        for (size_t i = 0; i < points; ++i) d.unit[i][k] = (double(strata[i]) + jitter(rng)) / double(points);
    }
    for (size_t i = 0; i < points; ++i)
        for (size_t k = 0; k < unknowns.size(); ++k)
            d.sets[i].emplace_back(unknowns[k].spec->key, value_text(unknowns[k], d.unit[i][k]));
    return d;
}

Json doubt_json(const std::vector<Unknown>& unknowns, const JointDesign& design, const std::vector<Json>& results,
                double run_fps, double reference_fps, double budget, unsigned frames) {
    std::vector<size_t> good;
    Json failed = Json::array();
    for (size_t i = 0; i < results.size(); ++i) {
        if (results[i].is_null() || results[i].contains("error") || results[i]["fps"].get<double>() <= 0 ||
            !results[i].contains("alone_fps"))
            failed.push_back({{"point", i}, {"error", results[i].value("error", std::string("no frame rate"))}});
        else
            good.push_back(i);
    }
    Json out = {
        {"points", results.size()}, {"frames", frames}, {"unknowns", unknowns.size()}, {"failed_points", failed}};
    if (good.size() < 2) return out;
    std::vector<double> fps;
    for (size_t i : good) fps.push_back(run_fps + results[i]["fps"].get<double>() - reference_fps);
    const double met = double(std::count_if(fps.begin(), fps.end(), [&](double f) { return f >= budget; }));
    out["fps"] = {{"p5", percentile(fps, 0.05)},
                  {"p50", percentile(fps, 0.5)},
                  {"p95", percentile(fps, 0.95)},
                  {"min", *std::min_element(fps.begin(), fps.end())},
                  {"max", *std::max_element(fps.begin(), fps.end())}};
    if (budget > 0) out["probability_met"] = met / double(fps.size());

    // The surrogate, on the resources every good point reports.
    Eigen::MatrixXd x(Eigen::Index(good.size()), Eigen::Index(feature_count(unknowns)));
    Eigen::VectorXd rate(x.rows());
    std::map<std::string, Eigen::VectorXd> log_alone;
    for (const auto& [resource, v] : results[good[0]]["alone_fps"].items())
        log_alone[resource] = Eigen::VectorXd(x.rows());
    for (Eigen::Index r = 0; r < x.rows(); ++r) {
        const Json& point = results[good[size_t(r)]];
        features(unknowns, design.unit[good[size_t(r)]], x.row(r));
        rate(r) = point["fps"].get<double>();
        for (auto it = log_alone.begin(); it != log_alone.end();) {
            const Json& a = point["alone_fps"];
            if (!a.contains(it->first) || a[it->first].get<double>() <= 0) {
                it = log_alone.erase(it);  // a resource not every point has cannot be fitted
                continue;
            }
            it->second(r) = std::log(a[it->first].get<double>());
            ++it;
        }
    }
    const Surrogate s = fit(x, log_alone, rate);
    double residual = 0, spread = 0;
    const double mean = rate.mean();
    for (Eigen::Index r = 0; r < x.rows(); ++r) {
        residual += std::pow(rate(r) - s.fps(x.row(r)), 2);
        spread += std::pow(rate(r) - mean, 2);
    }
    out["surrogate"] = {{"r2", spread > 0 ? 1 - residual / spread : 1.0},
                        {"method",
                         "per resource, log(frames/s it alone allows) linear in the unknowns; the least of them, "
                         "scaled to the points"},
                        {"sobol_samples", kSobolSamples}};
    out["sensitivity"] = sensitivity(unknowns, s, 2);
    return out;
}

}  // namespace surfvp
