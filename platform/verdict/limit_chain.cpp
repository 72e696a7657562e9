#include "platform/verdict/limit_chain.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <set>

#include "models/fhg/sequence_cache.h"
#include "platform/scenario/parameters.h"
#include "platform/scenario/block_params.h"
#include "platform/workload/surf_settings.h"

namespace surfvp {

Config verdict_variant(const Config& base, const std::vector<std::pair<std::string, std::string>>& sets) {
    return base.with(sets, "verdict");
}

namespace {
using Json = nlohmann::ordered_json;

// The parameter that moves the limiting resource's time, and how the frame rate follows it:
// +1 rises with the value, -1 falls; `linear` when the resource's time is proportional to the
// value (a clock's period, a count of cycles), which gives the search its first guess.
struct Axis {
    std::string key;
    int direction;
    bool linear;
};

// A CPU stalled on line fills this share of its busy time or more is limited by its memory too.
constexpr double kStalledShare = 0.1;

// By the limit's cause: a busy block's own clock (and the FHG's cycles per block; for a CPU
// stalled on fills, the memory's latency and its path's clock); a buffer coupling its depth; a
// block waiting on something, the clock of what it waits on.
std::vector<Axis> break_even_axes(const std::string& resource, const std::string& cause, const Json& point,
                                  const Config& config) {
    if (cause == "busy") {
        if (resource == "fhg") return {{"fhg.clock", +1, true}, {"fhg.cycles_per_block", -1, true}};
        if (resource == "iig") return {{"iig.clock", +1, true}};
        if (resource == "cpu") {
            std::vector<Axis> axes{{"cpu.clock", +1, true}};
            if (point.value("cpu_fill_stall_ms", 0.0) >= kStalledShare * point.value("cpu_ms_per_frame", 0.0)) {
                axes.push_back({"memory.latency", -1, false});
                axes.push_back({cpu_memory_on_plb1(config) ? "plb1.clock" : "mci.clock", +1, false});
            }
            return axes;
        }
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
        guess_ =
            clamp(axis.direction * (integer_ ? (axis.direction > 0 ? std::ceil(guess) : std::floor(guess)) : guess));
        step_ = integer_ ? 1 : 0.01 * std::abs(guess_);
    }

    // The next value to simulate, or nothing when the search is over.
    std::optional<double> next() {
        if (++runs_ > kMaxRuns) return std::nullopt;
        if (!lo_ && !hi_) return value(guess_);
        if (lo_ && hi_) {
            if (*hi_ - *lo_ <= tolerance()) return std::nullopt;
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

    // `met`: the point meets the budget, or this limit no longer holds it below (meets()).
    void record(double v, bool met, double fps) {
        const double u = axis_.direction * v;
        if (met) {
            if (!hi_ || u < *hi_) hi_ = u, hi_fps_ = fps;
        } else if (!lo_ || u > *lo_) {
            lo_ = u;
        }
    }

    std::optional<double> answer() const { return hi_ ? std::optional<double>(value(*hi_)) : std::nullopt; }

    // After the whole run missed at the answer: further towards meeting, by the search's
    // tolerance and then twice as far each time, or nothing when that leaves the range or the
    // nudges are used up.
    std::optional<double> nudge() {
        if (!hi_ || ++nudges_ > kMaxNudges) return std::nullopt;
        const double step = tolerance() * double(1 << (nudges_ - 1));
        const double next = *hi_ + step;
        if (next > u_max_) return std::nullopt;
        hi_ = next;
        return value(next);
    }
    const Axis& axis() const { return axis_; }
    const ParamSpec& spec() const { return spec_; }

    Json result(const Json& check) const {
        Json r = {{"parameter", axis_.key}, {"default", as_text(spec_, start_)}, {"runs", runs_ - 1}};
        if (hi_) {
            r["value"] = as_text(spec_, value(*hi_));
            r["searched"] = value(*hi_) < start_ ? "down" : "up";  // from the current value
            r["nudges"] = nudges_;
            r["fps"] = hi_fps_;
            r["bound"] = !lo_ ? (*hi_ <= u_min_ ? "met at the end of its range" : "") : "";
            r["check"] = check;
        } else {
            r["value"] = nullptr;
            r["note"] = runs_ > kMaxRuns
                            ? fmt::format("no value found in {} re-simulations", kMaxRuns)
                            : fmt::format("not met anywhere in {}'s range ({} to {})", axis_.key,
                                          axis_.direction > 0 ? "up" : "down", as_text(spec_, value(u_max_)));
        }
        return r;
    }

private:
    static constexpr int kMaxRuns = 24, kMaxNudges = 5;
    // How close the search brackets the answer: 0.1 % of a clock, one step of a count.
    double tolerance() const { return integer_ ? 1 : 1e-3 * std::abs(*hi_); }
    double clamp(double u) const { return std::min(u_max_, std::max(u_min_, u)); }
    double value(double u) const { return axis_.direction * u; }

    Axis axis_;
    const ParamSpec& spec_;
    double budget_, start_;
    bool integer_ = false;
    double u_min_ = 0, u_max_ = 0, guess_ = 0, step_ = 1;
    std::optional<double> lo_, hi_;
    double hi_fps_ = 0;
    int runs_ = 0, nudges_ = 0;
};

// A resource's frame rate alone in a point, or -1 when the point does not give it.
double alone(const Json& r, const std::string& resource) {
    return r.contains("alone_fps") && r["alone_fps"].contains(resource) ? r["alone_fps"][resource].get<double>() : -1;
}

// What a search asks of a point. A limit below the budget is relieved when the point meets the
// budget, or when another resource now limits and this one alone would allow the budget (so a
// second limit below the budget, which the chain's next step names, cannot hide the first
// one's break-even). A resource with headroom keeps it while the rate meets the budget, or,
// where the step starts below the budget (an earlier limit relieved while another holds the
// rate down), while the rate stays within 0.1 % (the searches' tolerance) of where it started.
struct Goal {
    std::string resource;
    double budget;
    bool relieve;      // the resource limits below the budget
    double floor_fps;  // keep: the rate to hold
    bool meets(const Json& r) const {
        if (r.contains("error")) return false;
        const double fps = r["fps"].get<double>();
        if (!relieve) return fps >= floor_fps;
        if (fps >= budget) return true;
        return !r["limit"].is_null() && r["limit"] != resource && alone(r, resource) >= budget;
    }
};

// The value an axis starts from in `config`: the FHG's cycles per block are its sequence's.
double start_value(const Axis& axis, const Config& config) {
    if (axis.key != "fhg.cycles_per_block") return config.base_value(axis.key);
    const Fhg::Params fhg = fhg_params(config);
    return Fhg::block_cycles(fhg::cached_sequence(fhg.sequence), fhg);
}

// The limit after `relieved` are: the run's own if it is another resource, else the resource
// with the least headroom among the rest.
std::pair<std::string, std::string> next_limit(const Json& point, const std::set<std::string>& relieved) {
    if (!point["limit"].is_null() && !relieved.count(point["limit"].get<std::string>()))
        return {point["limit"].get<std::string>(), point["limit_cause"].get<std::string>()};
    std::string least;
    double lowest = std::numeric_limits<double>::infinity();
    if (point.contains("alone_fps"))
        for (const auto& [name, fps] : point["alone_fps"].items())
            if (name != "accelerator pair" && !relieved.count(name) && fps.get<double>() < lowest)
                lowest = fps, least = name;
    return {least, "busy"};
}

}  // namespace

struct LimitChain::Step {
    std::vector<std::pair<std::string, std::string>> relieved;  // what was set to reach this step
    Config base;                                                // the reference with those set
    Json point;                                                 // its re-simulation
    std::string resource, cause;
    Goal goal;
    bool searched = false;  // its break-even (the last limit's is not)
    std::vector<std::unique_ptr<BreakEven>> searches;
    std::vector<Json> checks;
    size_t pending = 0;
};

LimitChain::LimitChain(const Config& config, const Config& reference, double budget, Resimulation& pool, size_t depth)
    : config_(config), reference_(reference), budget_(budget), pool_(pool), depth_(depth) {}

LimitChain::~LimitChain() = default;

void LimitChain::start(const Json& reference_point) {
    steps_.push_back(std::make_unique<Step>());
    steps_[0]->base = reference_;
    begin(0, reference_point);
}

void LimitChain::begin(size_t k, const Json& point) {
    Step& s = *steps_[k];
    s.point = point;
    if (point.contains("error") || point["fps"].get<double>() <= 0) return;
    std::set<std::string> relieved;
    for (size_t j = 0; j < k; ++j) relieved.insert(steps_[j]->resource);
    std::tie(s.resource, s.cause) = next_limit(point, relieved);
    if (s.resource.empty()) return;
    const double fps = point["fps"].get<double>(), own = alone(point, s.resource);
    s.goal = {s.resource, budget_, own < 0 ? fps < budget_ : own < budget_,
              fps >= budget_ ? budget_ : fps * (1 - 1e-3)};
    if (k + 1 == depth_ && k > 0) return;  // the last limit is named with its headroom; nothing comes after it
    s.searched = true;
    for (const Axis& axis : break_even_axes(s.resource, s.cause, point, s.base)) {
        s.searches.push_back(
            std::make_unique<BreakEven>(axis, start_value(axis, s.base), point["fps"].get<double>(), budget_));
        s.checks.emplace_back();
    }
    s.pending = s.searches.size();
    for (size_t i = 0; i < s.searches.size(); ++i) drive(k, i);
}

// A search asks for its next value when the last one is in, then for a check of the whole
// scenario at its answer.
void LimitChain::drive(size_t k, size_t i) {
    Step& s = *steps_[k];
    BreakEven& search = *s.searches[i];
    if (const auto v = search.next()) {
        pool_.submit(
            verdict_variant(s.base, {{search.axis().key, as_text(search.spec(), *v)}}),
            [this, k, i, v](const Json& r) {
                Step& step = *steps_[k];
                step.searches[i]->record(*v, step.goal.meets(r), r.contains("error") ? -1.0 : r["fps"].get<double>());
                drive(k, i);
            },
            Resimulation::point_summary, "", "none", true);
    } else if (const auto answer = search.answer()) {
        check(k, i, *answer);
    } else {
        done(k);
    }
}

void LimitChain::check(size_t k, size_t i, double value) {
    Step& s = *steps_[k];
    std::vector<std::pair<std::string, std::string>> sets = s.relieved;
    sets.emplace_back(s.searches[i]->axis().key, as_text(s.searches[i]->spec(), value));
    pool_.submit(
        verdict_variant(config_, sets),
        [this, k, i](const Json& r) {
            Step& step = *steps_[k];
            const bool met = step.goal.meets(r);
            if (!met && !r.contains("error"))
                if (const auto further = step.searches[i]->nudge()) return check(k, i, *further);
            step.checks[i] = r.contains("error") ? r
                                                 : Json{{"frames", surf_settings(config_).frames},
                                                        {"fps", r["fps"]},
                                                        {"met", met},
                                                        {"budget_met", r["fps"].get<double>() >= budget_},
                                                        {"limit", r["limit"]},
                                                        {"goal", step.goal.relieve ? "relieve" : "keep"}};
            done(k);
        },
        Resimulation::point_summary, "", "none", true);
}

// Once every search of step k is over, relieve its limit at the first break-even found and
// re-simulate for the next.
void LimitChain::done(size_t k) {
    Step& s = *steps_[k];
    if (--s.pending > 0 || k + 1 >= depth_) return;
    for (const auto& search : s.searches) {
        const auto answer = search->answer();
        if (!answer) continue;
        auto next = std::make_unique<Step>();
        next->relieved = s.relieved;
        next->relieved.emplace_back(search->axis().key, as_text(search->spec(), *answer));
        next->base = verdict_variant(reference_, next->relieved);
        steps_.push_back(std::move(next));
        pool_.submit(
            steps_.back()->base, [this, k](const Json& r) { begin(k + 1, r); }, Resimulation::point_summary, "", "none",
            true);
        return;
    }
}

Json LimitChain::json() const {
    Json chain = Json::array();
    for (const auto& s : steps_) {
        if (s->resource.empty()) continue;
        Json step = {{"resource", s->resource}, {"cause", s->cause}, {"fps", s->point["fps"]}};
        const Json alone = s->point.contains("alone_fps") && s->point["alone_fps"].contains(s->resource)
                               ? s->point["alone_fps"][s->resource]
                               : Json();
        step["alone_fps"] = alone;
        step["headroom"] = alone.is_null() || budget_ <= 0 ? Json() : Json(alone.get<double>() / budget_ - 1);
        Json relieved = Json::array();
        for (const auto& [key, value] : s->relieved) relieved.push_back({{"parameter", key}, {"value", value}});
        step["relieved"] = relieved;
        Json searches = Json::array();
        for (size_t i = 0; i < s->searches.size(); ++i) searches.push_back(s->searches[i]->result(s->checks[i]));
        step["break_even"] = searches;
        step["searched"] = s->searched;
        chain.push_back(step);
    }
    return chain;
}

}  // namespace surfvp
