#include "platform/verdict/verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <unistd.h>

#include "platform/catalog.h"
#include "platform/report/json_input.h"
#include "platform/report/run_summary.h"
#include "platform/run/progress_line.h"
#include "platform/report/report.h"
#include "platform/run/resimulation.h"
#include "platform/run/run.h"
#include "platform/verdict/doubt.h"
#include "platform/verdict/limit_chain.h"
#include "platform/verdict/tornado.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"
#include "platform/workload/describer.h"
#include "platform/workload/surf_settings.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr uint32_t kJointSeed = 1;
constexpr size_t kChainDepth =
    3;  // limits named, each relieved in turn  // the joint sample's: the same scenario samples the same points

// Whether a banded parameter can change anything in this scenario.
bool takes_effect(const ParamSpec& p, const Config& c) {
    if (p.key.rfind("smoke.", 0) == 0 || p.key.rfind("dma.", 0) == 0) return false;  // the test DMA: not in a SURF run
    // The cost models' parameters (FPGA resources, power) move no simulated figure: their
    // spread is the cost figures', not the frame rate's.
    if (p.key.rfind("fpga.", 0) == 0 || p.key.rfind("power.", 0) == 0) return false;
    // The FHG's fixed-point formats move the determinants, not the time (their word width,
    // fhg.det_bits, moves the traffic): `surfvp precision` measures what they cost in quality.
    if (p.key.rfind("fhg.", 0) == 0 && p.key.find("_bits") != std::string::npos && p.key != "fhg.det_bits")
        return false;
    if (p.key == "fhg.recip_shift") return false;
    if (p.key == "surf.threshold") return surf_settings(c).target_keypoints == 0;
    if (p.key == "plb1.arbitration") return cpu_memory_on_plb1(c);  // PLB1's only master otherwise
    return true;
}

bool same_value(const ParamSpec& p, const std::string& a, const std::string& b) {
    if (p.kind == ParamKind::choice || p.kind == ParamKind::text) return a == b;
    return parse_value(p, a) == parse_value(p, b);
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

double fps_of(const Json& point) {
    return point.is_null() || point.contains("error") ? -1 : point["fps"].get<double>();
}

// Each point's effect is its difference from the reference (the same frames, defaults); its
// frame rate is the whole run's plus that difference, which is what is judged against the
// budget (so a point flips the verdict of the run the report gives, not of the reference).
Json band_json(const std::vector<BandAxis>& axes, const Json& reference, double run_fps, double budget,
               unsigned frames) {
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
    return {{"frames", frames},    {"reference_fps", ref}, {"run_fps", run_fps},      {"low_fps", lowest},
            {"high_fps", highest}, {"flipping", at_risk},  {"failed_points", failed}, {"axes", rows}};
}

// The settings that move the CPU's time, each value other than the scenario's: the software's
// and the FPU's precision.
std::vector<std::pair<std::string, std::string>> software_settings(const Config& c) {
    std::vector<std::pair<std::string, std::string>> points;
    const SurfWorkloadSettings s = surf_settings(c);
    points.emplace_back("fpu.precision", pipeline_params(c).double_precision != 0 ? "single" : "double");
    points.emplace_back("surf.haar", s.haar == surf::HaarMode::exact ? "rounded" : "exact");
    points.emplace_back("surf.upright", s.upright ? "off" : "on");
    points.emplace_back("surf.descriptor", s.descriptor == surf::DescriptorKind::msurf ? "surf" : "msurf");
    const uint64_t target = s.target_keypoints;
    for (const uint64_t k : {50, 100, 150, 200})
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
    for (size_t i = 0; i < settings.size(); ++i)
        rows.push_back(row(settings[i].first + " = " + settings[i].second, results[i]));
    return rows;
}

// The limit and its cause, and the break-even of each axis the search found ("fhg.clock =
// 104.661 MHz or fhg.cycles_per_block = 50 cycles"), as the statement's middle.
std::string limit_text(const Json& limit, const Json& break_even) {
    std::string s;
    if (!text_at(limit, "/resource").empty())
        s = fmt::format("; limited by {} ({})", text_at(limit, "/resource"), text_at(limit, "/cause"));
    std::vector<std::string> found;
    if (break_even.is_array())
        for (const Json& b : break_even)
            if (text_at(b, "/bound").empty() && !text_at(b, "/value").empty())
                found.push_back(text_at(b, "/parameter") + " = " + text_at(b, "/value"));
    if (!found.empty()) s += "; break-even " + fmt::format("{}", fmt::join(found, " or "));
    return s;
}

std::string statement(double fps, double budget, const Json& limit, const Json& break_even, const Json& band,
                      const Json& doubt) {
    const double margin = 100 * (fps / budget - 1);
    const bool met = fps >= budget;
    std::string s = fmt::format("{} at defaults ({:.2f} frames/s, {:+.1f} % against {:g}){}", met ? "met" : "missed",
                                fps, margin, budget, limit_text(limit, break_even));
    if (!doubt.is_null() && doubt.contains("fps"))
        s += fmt::format(
            "; over the unknowns jointly {:.2f} to {:.2f} frames/s (5th to 95th percentile), met with "
            "probability {:.0f} %",
            doubt["fps"]["p5"].get<double>(), doubt["fps"]["p95"].get<double>(),
            100 * doubt["probability_met"].get<double>());
    if (band.is_null()) return s;
    std::vector<std::string> names;
    for (const Json& n : band["flipping"]) names.push_back(n.get<std::string>());
    if (names.empty())
        return s + fmt::format("; {} under every unknown alone ({:.2f} to {:.2f} frames/s)", met ? "met" : "missed",
                               band["low_fps"].get<double>(), band["high_fps"].get<double>());
    return s + fmt::format("; {} with {} alone", met ? "at risk" : "met", fmt::join(names, ", "));
}

}  // namespace

bool verdict_requested(const Config& config) {
    const VerdictSettings v = verdict_settings(config);
    return run_settings(config).workload == "surf" && (v.band || v.break_even || v.software);
}

namespace {

// What the verdict re-simulates beside the whole run, and their results as they come in (the
// re-simulations' callbacks hold pointers into it: nothing is added once they are submitted).
struct VerdictWork {
    double budget = 0;
    unsigned frames = 0;  // the re-simulations' frame count
    bool band = false, break_even = false, software = false;
    std::vector<BandAxis> unknown_axes, changes;  // the unknowns one at a time (the tornado); what a review can change
    std::vector<Unknown> unknowns;                // and jointly
    JointDesign joint;
    std::vector<Json> joint_results;
    std::vector<std::pair<std::string, std::string>> settings;  // the software's what-ifs
    std::vector<Json> software_results;
    Json base, reference_point;  // the whole run; the scenario at the re-simulations' frame count
};

VerdictWork plan_verdict(const Config& config) {
    VerdictWork w;
    const VerdictSettings v = verdict_settings(config);
    w.budget = surf_settings(config).budget_fps;
    w.frames = resimulation_frames(config);
    w.band = v.band;
    w.break_even = v.break_even && w.budget > 0;
    w.software = v.software;
    std::vector<const ParamSpec*> effective;
    if (w.band)
        for (const ParamSpec* p : band_parameters())
            if (takes_effect(*p, config)) {
                effective.push_back(p);
                (p->role == ParamRole::unknown ? w.unknown_axes : w.changes)
                    .push_back({p, config.value(p->key), {p->band.low, {}}, {p->band.high, {}}});
            }
    w.unknowns = unknowns_of(effective, config);
    w.joint = joint_design(w.unknowns, w.band ? size_t(v.samples) : 0, kJointSeed);
    w.joint_results.resize(w.joint.sets.size());
    if (w.software) w.settings = software_settings(config);
    w.software_results.resize(w.settings.size());
    return w;
}

// The band's sides (each away from the current value), the joint sample and the software's
// what-ifs, each the reference with its settings.
void submit_variants(VerdictWork& w, Resimulation& pool, const Config& reference) {
    for (std::vector<BandAxis>* axes : {&w.unknown_axes, &w.changes})
        for (BandAxis& axis : *axes)
            for (BandSide* side : {&axis.low, &axis.high}) {
                if (same_value(*axis.spec, side->value, axis.current)) continue;
                pool.submit(verdict_variant(reference, {{axis.spec->key, side->value}}),
                            [side](const Json& r) { side->result = r; });
            }
    for (size_t i = 0; i < w.joint.sets.size(); ++i)
        pool.submit(verdict_variant(reference, w.joint.sets[i]), [&w, i](const Json& r) { w.joint_results[i] = r; });
    for (size_t i = 0; i < w.settings.size(); ++i)
        pool.submit(verdict_variant(reference, {w.settings[i]}), [&w, i](const Json& r) { w.software_results[i] = r; });
}

// The verdict from the results: the budget and margin, the chain of limits, the band with its
// tornado (written into `out`), the doubt, the software's what-ifs and the statement.
Json verdict_json(VerdictWork& w, const LimitChain& chain, const std::string& out) {
    Json verdict;
    const double fps = RunSummary::of(w.base).fps, budget = w.budget;
    if (budget > 0) {
        verdict["budget_fps"] = budget;
        verdict["fps"] = fps;
        verdict["met"] = fps >= budget;
        verdict["margin"] = fps / budget - 1;
    }
    if (w.base.contains("limit")) verdict["limit"] = w.base["limit"];
    if (w.break_even) {
        verdict["chain"] = chain.json();
        verdict["break_even"] = verdict["chain"].empty() ? Json::array() : verdict["chain"][0]["break_even"];
    }
    Json band_result, doubt;
    if (w.band) {
        band_result = band_json(w.unknown_axes, w.reference_point, fps, budget, w.frames);
        verdict["band"] = band_result;
        verdict["changes"] = band_json(w.changes, w.reference_point, fps, budget, w.frames);
        if (!w.joint.sets.empty()) {
            doubt = doubt_json(w.unknowns, w.joint, w.joint_results, fps, fps_of(w.reference_point), budget, w.frames);
            verdict["doubt"] = doubt;
        }
        const std::string tornado = tornado_svg(band_result, budget);
        write_file_atomically((fs::path(out) / "tornado.svg").string(), tornado);
        w.base["figures"]["tornado_svg"] = tornado;  // for report.html
        w.base["outputs"].push_back("tornado.svg");
    }
    if (w.software) verdict["software"] = software_json(w.settings, w.software_results, w.reference_point, fps, budget);
    if (budget > 0)
        verdict["statement"] = statement(fps, budget, verdict.value("limit", Json()),
                                         verdict.value("break_even", Json()), band_result, doubt);
    return verdict;
}

}  // namespace

int run_with_verdict(const Config& config, const std::string& out, const std::string& trace, bool quiet) {
    VerdictWork w = plan_verdict(config);
    // The re-simulations ask what-ifs of other parameters with the model's datapath: it gives
    // the verilated one's figures at a hundredth of its time, and takes the break-even's
    // fhg.cycles_per_block (fhg.model=rtl checks the whole run itself: docs/rtl.md).
    const Config modelled = verdict_variant(config, {{"fhg.model", "core"}});
    // The re-simulations run one thread each: the jobs share the cores (run.parallel moves no figure).
    const Config reference =
        verdict_variant(modelled, {{"surf.frames", std::to_string(w.frames)}, {"run.parallel", "off"}});
    // Prepare once what every child needs: the frames, the calibration, the FHG's sequences.
    Resimulation::prepare(config);
    Resimulation::prepare(reference);
    Resimulation pool(verdict_settings(config).jobs, fs::path(out) / fmt::format(".verdict.{}", ::getpid()));
    LimitChain chain(modelled, reference, w.budget, pool, w.break_even ? kChainDepth : 0);
    // The reference first: it names the limit the chain starts from, while the whole run and
    // the band's points go on.
    pool.submit(reference, [&](const Json& r) {
        w.reference_point = r;
        if (w.break_even) chain.start(r);
    });
    pool.submit(
        config, [&](const Json& r) { w.base = r; }, Resimulation::whole, out, trace);
    submit_variants(w, pool, reference);
    {
        // The break-even searches end when they find their value: their share of the total is
        // an estimate, fixed here.
        const size_t about = pool.submitted() + LimitChain::expected_runs(w.break_even ? kChainDepth : 0);
        ProgressLine progress(quiet, config.name, 0.0, 0.5, 5.0);
        pool.run([&](size_t done, size_t) { progress.steps(done, about, "verdict re-simulations", w.break_even); });
    }
    if (w.base.contains("error")) {
        if (w.base["exit"] == 2) throw ConfigError(w.base["error"].get<std::string>());
        throw std::runtime_error(w.base["error"].get<std::string>());
    }
    w.base["verdict"] = verdict_json(w, chain, out);
    return write_run(config, out, w.base);
}

}  // namespace surfvp
