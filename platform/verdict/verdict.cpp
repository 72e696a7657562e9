#include "platform/verdict/verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <unistd.h>

#include "platform/run/progress_line.h"
#include "platform/report/report.h"
#include "platform/run/resimulation.h"
#include "platform/run/run.h"
#include "platform/verdict/doubt.h"
#include "platform/verdict/limit_chain.h"
#include "platform/verdict/tornado.h"

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
    if (p.key == "surf.threshold") return c.count("surf.target_keypoints") == 0;
    if (p.key == "plb1.arbitration") return c.choice("cpu.memory_path") == "plb1";  // PLB1's only master otherwise
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
    points.emplace_back("fpu.precision", c.choice("fpu.precision") == "double" ? "single" : "double");
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
    for (size_t i = 0; i < settings.size(); ++i)
        rows.push_back(row(settings[i].first + " = " + settings[i].second, results[i]));
    return rows;
}

std::string statement(double fps, double budget, const Json& band, const Json& doubt) {
    const double margin = 100 * (fps / budget - 1);
    const bool met = fps >= budget;
    std::string s =
        met ? fmt::format("met at defaults ({:.2f} frames/s, {:+.1f} % against {:g})", fps, margin, budget)
            : fmt::format("missed at defaults ({:.2f} frames/s, {:+.1f} % against {:g})", fps, margin, budget);
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
    return config.choice("run.workload") == "surf" &&
           (config.choice("verdict.band") == "on" || config.choice("verdict.break_even") == "on" ||
            config.choice("verdict.software") == "on");
}

int run_with_verdict(const Config& config, const std::string& out, const std::string& trace, bool quiet) {
    const double budget = config.real("budget.fps");
    // Enough frames for every pair to reach its steady state (throughput needs pairs + 1).
    const unsigned frames = unsigned(std::min(
        std::max(config.count("verdict.frames"), config.count("soc.accelerators") + 1), config.count("surf.frames")));
    const bool want_band = config.choice("verdict.band") == "on";
    const bool want_break_even = config.choice("verdict.break_even") == "on" && budget > 0;
    // The re-simulations run one thread each: the jobs share the cores (run.parallel moves no figure).
    const Config reference =
        verdict_variant(config, {{"surf.frames", std::to_string(frames)}, {"run.parallel", "off"}});

    // Prepare once what every child needs: the frames, the calibration, the FHG's sequences.
    Resimulation::prepare(config);
    Resimulation::prepare(reference);

    Resimulation pool(unsigned(config.count("verdict.jobs")), fs::path(out) / fmt::format(".verdict.{}", ::getpid()));
    Json base, reference_point;
    LimitChain chain(config, reference, budget, pool, want_break_even ? kChainDepth : 0);
    // The reference (the scenario at the re-simulations' frame count) first: it names the
    // limit the chain starts from, while the whole run and the band's points go on.
    pool.submit(reference, [&](const Json& r) {
        reference_point = r;
        if (want_break_even) chain.start(r);
    });
    pool.submit(
        config, [&](const Json& r) { base = r; }, Resimulation::whole, out, trace);

    // The band: the unknowns one at a time (the tornado) and jointly; design choices and the
    // workload one at a time, apart (what a review can change).
    std::vector<BandAxis> band, changes;
    std::vector<const ParamSpec*> effective;
    if (want_band)
        for (const ParamSpec* p : band_parameters())
            if (takes_effect(*p, config)) {
                effective.push_back(p);
                (p->role == ParamRole::unknown ? band : changes)
                    .push_back({p, config.value(p->key), {p->band.low, {}}, {p->band.high, {}}});
            }
    for (std::vector<BandAxis>* axes : {&band, &changes})
        for (BandAxis& axis : *axes)
            for (BandSide* side : {&axis.low, &axis.high}) {
                if (same_value(*axis.spec, side->value, axis.current)) continue;
                pool.submit(verdict_variant(reference, {{axis.spec->key, side->value}}),
                            [side](const Json& r) { side->result = r; });
            }
    const std::vector<Unknown> unknowns = unknowns_of(effective, config);
    const JointDesign joint =
        joint_design(unknowns, want_band ? size_t(config.count("verdict.samples")) : 0, kJointSeed);
    std::vector<Json> joint_results(joint.sets.size());
    for (size_t i = 0; i < joint.sets.size(); ++i)
        pool.submit(verdict_variant(reference, joint.sets[i]),
                    [&joint_results, i](const Json& r) { joint_results[i] = r; });
    const bool want_software = config.choice("verdict.software") == "on";
    const auto settings =
        want_software ? software_settings(config) : std::vector<std::pair<std::string, std::string>>{};
    std::vector<Json> software(settings.size());
    for (size_t i = 0; i < settings.size(); ++i)
        pool.submit(verdict_variant(reference, {settings[i]}), [&software, i](const Json& r) { software[i] = r; });
    {
        ProgressLine progress(quiet, config.name, 0.0, 0.5, 5.0);
        pool.run([&](size_t done, size_t total) {
            progress.update(
                [&](double wall) { return fmt::format("verdict: {}/{} re-simulations, {:.1f} s", done, total, wall); });
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
        verdict["chain"] = chain.json();
        verdict["break_even"] = verdict["chain"].empty() ? Json::array() : verdict["chain"][0]["break_even"];
    }
    Json band_result, doubt;
    if (want_band) {
        band_result = band_json(band, reference_point, fps, budget, frames);
        verdict["band"] = band_result;
        verdict["changes"] = band_json(changes, reference_point, fps, budget, frames);
        if (!joint.sets.empty()) {
            doubt = doubt_json(unknowns, joint, joint_results, fps, fps_of(reference_point), budget, frames);
            verdict["doubt"] = doubt;
        }
        write_file_atomically((fs::path(out) / "tornado.svg").string(), tornado_svg(band_result, budget));
        base["outputs"].push_back("tornado.svg");
    }
    if (want_software) verdict["software"] = software_json(settings, software, reference_point, fps, budget);
    if (budget > 0) verdict["statement"] = statement(fps, budget, band_result, doubt);
    base["verdict"] = verdict;
    return write_run(config, out, base);
}

}  // namespace surfvp
