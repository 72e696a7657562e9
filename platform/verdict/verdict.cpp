#include "platform/verdict/verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <unistd.h>

#include "models/fhg/sequence_cache.h"
#include "platform/cli/progress_line.h"
#include "platform/report/report.h"
#include "platform/sweep/resimulation.h"
#include "platform/run/run.h"
#include "platform/soc.h"
#include "platform/verdict/tornado.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// The parameter that moves the limiting resource's time, and how the frame rate follows it:
// +1 rises with the value, -1 falls; `linear` when the resource's time is proportional to the
// value (a clock's period, a count of cycles), which gives the search its first guess.
struct Axis {
    std::string key;
    int direction;
    bool linear;
};

// By the limit's cause: a busy block's own clock (and the FHG's cycles per block); a buffer
// coupling its depth; a block waiting on something, the clock of what it waits on.
std::vector<Axis> break_even_axes(const std::string& resource, const std::string& cause) {
    if (cause == "busy") {
        if (resource == "fhg") return {{"fhg.clock", +1, true}, {"fhg.cycles_per_block", -1, true}};
        if (resource == "iig") return {{"iig.clock", +1, true}};
        if (resource == "cpu") return {{"cpu.clock", +1, true}};
        if (resource == "plb2 write" || resource == "plb2 read") return {{"plb2.clock", +1, true}};
        if (resource == "plb1") return {{"plb1.clock", +1, true}};
        if (resource == "mci") return {{"mci.clock", +1, true}};
        if (resource == "ddr") return {{"memory.clock", +1, true}};
        return {};
    }
    if (resource == "line fifo") return {{"fhg.fifo_lines", +1, false}};
    if (resource == "task slots") return {{"surf.tasks_in_flight", +1, false}};
    if (cause == "image DMA read" || cause == "integral DMA write" || cause == "determinant DMA write")
        return {{"plb2.clock", +1, false}};
    if (cause == "line FIFO empty") return {{"iig.clock", +1, false}};
    if (cause == "PixelBus back-pressure") return {{"fhg.clock", +1, false}};
    return {};
}

// A search value as a scenario writes it: a clock in MHz to the kHz (format_value would pick
// the unit that makes it whole, "118353 kHz"), a count whole.
std::string as_text(const ParamSpec& spec, double value) {
    if (spec.kind == ParamKind::frequency) return fmt::format("{} MHz", std::round(value / 1e3) / 1e3);
    return format_value(spec, std::round(value));
}

// The search for the value at which the frame rate just meets the budget: in u = direction x
// value the frame rate rises, and the answer is the smallest u that meets it. A first guess
// (the linear model, or one step), then steps that double until the answer is bracketed, then
// bisection to 0.1 % of the value (a clock) or one step (a count). A value the platform
// refuses counts as a miss.
class BreakEven {
public:
    BreakEven(const Axis& axis, double start, double start_fps, double budget)
        : axis_(axis), spec_(*find_parameter(axis.key)), budget_(budget), start_(start) {
        integer_ = spec_.kind != ParamKind::frequency;
        const double lowest = std::max(spec_.min, 1.0);  // fhg.cycles_per_block = 0 means "the sequence's"
        u_min_ = axis.direction > 0 ? lowest : -spec_.max;
        u_max_ = axis.direction > 0 ? spec_.max : -lowest;
        double guess = start + (start_fps >= budget ? -axis.direction : axis.direction);
        if (axis.linear && start_fps > 0)
            guess = axis.direction > 0 ? start * budget / start_fps : start * start_fps / budget;
        guess_ = clamp(axis.direction * (integer_ ? (axis.direction > 0 ? std::ceil(guess) : std::floor(guess)) : guess));
        step_ = integer_ ? 1 : 0.01 * std::abs(guess_);
    }

    // The next value to simulate, or nothing when the search is over.
    std::optional<double> next() {
        if (++runs_ > kMaxRuns) return std::nullopt;
        if (!lo_ && !hi_) return value(guess_);
        if (lo_ && hi_) {
            const double tolerance = integer_ ? 1 : 1e-3 * std::abs(*hi_);
            if (*hi_ - *lo_ <= tolerance) return std::nullopt;
            const double mid = integer_ ? std::floor((*lo_ + *hi_) / 2) : (*lo_ + *hi_) / 2;
            return value(mid);
        }
        if (hi_) {  // meets: look lower
            if (*hi_ <= u_min_) return std::nullopt;
            const double u = clamp(*hi_ - step_);
            step_ *= 2;
            return value(u);
        }
        if (*lo_ >= u_max_) return std::nullopt;  // fails even at the range's end
        const double u = clamp(*lo_ + step_);
        step_ *= 2;
        return value(u);
    }

    void record(double v, double fps) {  // fps < 0: the point failed
        const double u = axis_.direction * v;
        if (fps >= budget_) {
            if (!hi_ || u < *hi_) hi_ = u, hi_fps_ = fps;
        } else if (!lo_ || u > *lo_) {
            lo_ = u;
        }
    }

    std::optional<double> answer() const { return hi_ ? std::optional<double>(value(*hi_)) : std::nullopt; }
    const Axis& axis() const { return axis_; }
    const ParamSpec& spec() const { return spec_; }

    Json result(const Json& check) const {
        Json r = {{"parameter", axis_.key}, {"default", as_text(spec_, start_)}, {"runs", runs_ - 1}};
        if (hi_) {
            r["value"] = as_text(spec_, value(*hi_));
            r["fps"] = hi_fps_;
            r["bound"] = !lo_ ? (*hi_ <= u_min_ ? "met at the end of its range" : "") : "";
            r["check"] = check;
        } else {
            r["value"] = nullptr;
            r["note"] = runs_ > kMaxRuns ? fmt::format("no value found in {} re-simulations", kMaxRuns)
                                         : fmt::format("not met anywhere in {}'s range (up to {})", axis_.key,
                                                       as_text(spec_, value(u_max_)));
        }
        return r;
    }

private:
    static constexpr int kMaxRuns = 24;
    double clamp(double u) const { return std::min(u_max_, std::max(u_min_, u)); }
    double value(double u) const { return axis_.direction * u; }

    Axis axis_;
    const ParamSpec& spec_;
    double budget_, start_;
    bool integer_ = false;
    double u_min_ = 0, u_max_ = 0, guess_ = 0, step_ = 1;
    std::optional<double> lo_, hi_;
    double hi_fps_ = 0;
    int runs_ = 0;
};

// Whether a banded parameter can change anything in this scenario.
bool takes_effect(const ParamSpec& p, const Config& c) {
    if (p.key.rfind("smoke.", 0) == 0 || p.key.rfind("dma.", 0) == 0) return false;  // the test DMA: not in a SURF run
    // The cost models' parameters (FPGA resources, power) move no simulated figure: their
    // spread is the cost figures', not the frame rate's.
    if (p.key.rfind("fpga.", 0) == 0 || p.key.rfind("power.", 0) == 0) return false;
    if (p.key == "surf.threshold") return c.count("surf.target_keypoints") == 0;
    if (p.key == "plb1.arbitration") return c.choice("cpu.memory_path") == "plb1";  // PLB1's only master otherwise
    return true;
}

bool same_value(const ParamSpec& p, const std::string& a, const std::string& b) {
    if (p.kind == ParamKind::choice || p.kind == ParamKind::text) return a == b;
    return parse_value(p, a) == parse_value(p, b);
}

Config with(const Config& base, const std::vector<std::pair<std::string, std::string>>& sets) {
    Config c = base;
    for (const auto& [key, value] : sets) c.set(key, value, "verdict");
    return c;
}

struct BandSide {
    std::string value;
    Json result;  // the point's summary, or null when this side is the current value
};
struct BandAxis {
    const ParamSpec* spec;
    std::string current;
    BandSide low, high;
};

double fps_of(const Json& point) { return point.is_null() || point.contains("error") ? -1 : point["fps"].get<double>(); }

// Each point's effect is its difference from the reference (the same frames, defaults); its
// frame rate is the whole run's plus that difference, which is what is judged against the
// budget (so a point flips the verdict of the run the report gives, not of the reference).
Json band_json(const std::vector<BandAxis>& axes, const Json& reference, double run_fps, double budget, unsigned frames) {
    const double ref = fps_of(reference);
    double lowest = run_fps, highest = run_fps;
    Json rows = Json::array(), at_risk = Json::array(), failed = Json::array();
    for (const BandAxis& a : axes) {
        Json row = {{"parameter", a.spec->key}, {"value", a.current}, {"why", a.spec->band.why}};
        double effect = 0;
        bool flips = false;
        for (const auto& [name, side] : {std::pair{"low", &a.low}, std::pair{"high", &a.high}}) {
            Json s = {{"value", side->value}};
            if (side->result.is_null()) {
                s["fps"] = nullptr;  // this side is the current value
            } else if (side->result.contains("error")) {
                s["error"] = side->result["error"];
                failed.push_back(fmt::format("{} = {}", a.spec->key, side->value));
            } else {
                const double point = fps_of(side->result), fps = run_fps + point - ref;
                s["fps"] = fps;
                s["point_fps"] = point;
                s["limit"] = side->result["limit"];
                lowest = std::min(lowest, fps);
                highest = std::max(highest, fps);
                effect = std::max(effect, std::abs(point - ref));
                if (budget > 0 && (fps >= budget) != (run_fps >= budget)) {
                    flips = true;
                    at_risk.push_back(fmt::format("{} = {}", a.spec->key, side->value));
                }
            }
            row[name] = s;
        }
        row["effect_fps"] = effect;
        row["flips_verdict"] = flips;
        rows.push_back(row);
    }
    std::stable_sort(rows.begin(), rows.end(), [](const Json& a, const Json& b) {
        return a["effect_fps"].get<double>() > b["effect_fps"].get<double>();
    });
    return {{"frames", frames}, {"reference_fps", ref}, {"run_fps", run_fps}, {"low_fps", lowest}, {"high_fps", highest},
            {"flipping", at_risk}, {"failed_points", failed}, {"axes", rows}};
}

// The software settings that move the CPU's time, each value other than the scenario's.
std::vector<std::pair<std::string, std::string>> software_settings(const Config& c) {
    std::vector<std::pair<std::string, std::string>> points;
    points.emplace_back("surf.haar", c.choice("surf.haar") == "exact" ? "rounded" : "exact");
    points.emplace_back("surf.upright", c.choice("surf.upright") == "on" ? "off" : "on");
    const int64_t target = c.count("surf.target_keypoints");
    for (const int64_t k : {50, 100, 150, 200})
        if (target > 0 && k != target) points.emplace_back("surf.target_keypoints", std::to_string(k));
    return points;
}

// Like the band's points: the run's frame rate plus each point's effect on the reference.
Json software_json(const std::vector<std::pair<std::string, std::string>>& settings, const std::vector<Json>& results,
                   const Json& reference, double run_fps, double budget) {
    const double ref = fps_of(reference);
    auto row = [&](const std::string& setting, const Json& r) {
        Json out = {{"setting", setting}};
        if (r.contains("error")) {
            out["error"] = r["error"];
            return out;
        }
        out["fps"] = run_fps + fps_of(r) - ref;
        out["point_fps"] = fps_of(r);
        out["cpu_ms_per_frame"] = r.value("cpu_ms_per_frame", 0.0);
        out["cpu_alone_fps"] = r.value("cpu_alone_fps", 0.0);
        out["limit"] = r["limit"];
        out["keypoints_per_frame"] = r["keypoints_per_frame"];
        if (budget > 0) out["met"] = out["fps"].get<double>() >= budget;
        return out;
    };
    Json rows = Json::array({row("as the scenario", reference)});
    for (size_t i = 0; i < settings.size(); ++i) rows.push_back(row(settings[i].first + " = " + settings[i].second, results[i]));
    return rows;
}

std::string statement(double fps, double budget, const Json& band) {
    const double margin = 100 * (fps / budget - 1);
    const bool met = fps >= budget;
    std::string s = met ? fmt::format("met at defaults ({:.2f} frames/s, {:+.1f} % against {:g})", fps, margin, budget)
                        : fmt::format("missed at defaults ({:.2f} frames/s, {:+.1f} % against {:g})", fps, margin, budget);
    if (band.is_null()) return s;
    std::vector<std::string> names;
    for (const Json& n : band["flipping"]) names.push_back(n.get<std::string>());
    if (names.empty())
        return s + fmt::format("; {} under every assumption of the band ({:.2f} to {:.2f} frames/s)", met ? "met" : "missed",
                               band["low_fps"].get<double>(), band["high_fps"].get<double>());
    return s + fmt::format("; {} under assumptions {}", met ? "at risk" : "met", fmt::join(names, ", "));
}

}  // namespace

bool verdict_requested(const Config& config) {
    return config.choice("run.workload") == "surf" &&
           (config.choice("verdict.band") == "on" || config.choice("verdict.break_even") == "on" ||
            config.choice("verdict.software") == "on");
}

int run_with_verdict(const Config& config, const std::string& out, const std::string& trace, bool quiet) {
    const double budget = config.real("budget.fps");
    // Enough frames for every pair to reach its steady state (throughput needs pairs + 1).
    const unsigned frames = unsigned(std::min(std::max(config.count("verdict.frames"), config.count("soc.accelerators") + 1),
                                              config.count("surf.frames")));
    const bool want_band = config.choice("verdict.band") == "on";
    const bool want_break_even = config.choice("verdict.break_even") == "on" && budget > 0;
    const Config reference = with(config, {{"surf.frames", std::to_string(frames)}});

    // Prepare once what every child needs: the frames, the calibration, the FHG's sequences.
    Resimulation::prepare(config);
    Resimulation::prepare(reference);

    Resimulation pool(unsigned(config.count("verdict.jobs")),
                      fs::path(out) / fmt::format(".verdict.{}", ::getpid()));
    Json base, reference_point;
    std::vector<std::unique_ptr<BreakEven>> searches;
    std::vector<Json> checks;
    // A break-even search asks for its next value when the last one is in, then for a check
    // of the whole scenario at the answer.
    std::function<void(size_t)> step = [&](size_t i) {
        BreakEven& s = *searches[i];
        if (const auto v = s.next()) {
            pool.submit(
                with(reference, {{s.axis().key, as_text(s.spec(), *v)}}),
                [&, i, v](const Json& r) {
                    searches[i]->record(*v, r.contains("error") ? -1.0 : r["fps"].get<double>());
                    step(i);
                },
                Resimulation::point_summary, "", "none", true);
        } else if (const auto answer = s.answer()) {
            pool.submit(
                with(config, {{s.axis().key, as_text(s.spec(), *answer)}}),
                [&, i](const Json& r) {
                    checks[i] = r.contains("error") ? r : Json{{"frames", config.count("surf.frames")}, {"fps", r["fps"]},
                                                                {"met", r["fps"].get<double>() >= budget}};
                },
                Resimulation::point_summary, "", "none", true);
        }
    };
    // The reference (the scenario at the re-simulations' frame count) first: it names the
    // limit the searches start from, while the whole run and the band's points go on.
    pool.submit(reference, [&](const Json& r) {
        reference_point = r;
        if (!want_break_even || r.contains("error") || r["limit"].is_null() || r["fps"].get<double>() <= 0) return;
        for (const Axis& axis : break_even_axes(r["limit"].get<std::string>(), r["limit_cause"].get<std::string>())) {
            const Fhg::Params fhg = fhg_params(config);
            const double start = axis.key == "fhg.cycles_per_block"
                                     ? Fhg::block_cycles(fhg::cached_sequence(fhg.sequence), fhg)
                                     : config.base_value(axis.key);
            searches.push_back(std::make_unique<BreakEven>(axis, start, r["fps"].get<double>(), budget));
            checks.emplace_back();
            step(searches.size() - 1);
        }
    });
    pool.submit(config, [&](const Json& r) { base = r; }, Resimulation::whole, out, trace);

    std::vector<BandAxis> band;
    if (want_band)
        for (const ParamSpec* p : band_parameters())
            if (takes_effect(*p, config)) band.push_back({p, config.value(p->key), {p->band.low, {}}, {p->band.high, {}}});
    for (BandAxis& axis : band)
        for (BandSide* side : {&axis.low, &axis.high}) {
            if (same_value(*axis.spec, side->value, axis.current)) continue;
            pool.submit(with(reference, {{axis.spec->key, side->value}}), [side](const Json& r) { side->result = r; });
        }
    const bool want_software = config.choice("verdict.software") == "on";
    const auto settings = want_software ? software_settings(config) : std::vector<std::pair<std::string, std::string>>{};
    std::vector<Json> software(settings.size());
    for (size_t i = 0; i < settings.size(); ++i)
        pool.submit(with(reference, {settings[i]}), [&software, i](const Json& r) { software[i] = r; });
    {
        ProgressLine progress(quiet, config.name, 0.0, 0.5, 5.0);
        pool.run([&](size_t done, size_t total) {
            progress.update([&](double wall) { return fmt::format("verdict: {}/{} re-simulations, {:.1f} s", done, total, wall); });
        });
    }
    if (base.contains("error")) {
        if (base["exit"] == 2) throw ConfigError(base["error"].get<std::string>());
        throw std::runtime_error(base["error"].get<std::string>());
    }

    Json verdict;
    const double fps = base.value("throughput_fps", 0.0);
    if (budget > 0) {
        verdict["budget_fps"] = budget;
        verdict["fps"] = fps;
        verdict["met"] = fps >= budget;
        verdict["margin"] = fps / budget - 1;
    }
    if (base.contains("limit")) verdict["limit"] = base["limit"];
    if (want_break_even) {
        Json all = Json::array();
        for (size_t i = 0; i < searches.size(); ++i) all.push_back(searches[i]->result(checks[i]));
        verdict["break_even"] = all;
    }
    Json band_result;
    if (want_band) {
        band_result = band_json(band, reference_point, fps, budget, frames);
        verdict["band"] = band_result;
        write_file_atomically((fs::path(out) / "tornado.svg").string(), tornado_svg(band_result, budget));
        base["outputs"].push_back("tornado.svg");
    }
    if (want_software) verdict["software"] = software_json(settings, software, reference_point, fps, budget);
    if (budget > 0) verdict["statement"] = statement(fps, budget, band_result);
    base["verdict"] = verdict;
    return write_run(config, out, base);
}

}  // namespace surfvp
