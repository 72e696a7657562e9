// The verdict with its doubt: the break-even value found by re-simulation really is the edge
// of the budget, and the assumption band re-simulates every banded assumption and says which
// flip the verdict. On a 512x384 frame (the same scenario, four times fewer blocks) to be quick.
#include <filesystem>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <map>
#include <set>
#include <nlohmann/json.hpp>

#include "cli.h"

namespace surfvp {
namespace {
using test::fresh_dir;
using test::fresh_path;
using test::kBudget;
using test::slurp;
using test::surfvp;

// 512x384 at ~20 keypoints, FHG-bound: 53 cycles x 49,152 blocks at 100 MHz, 38.4 frames/s
// (the CPU's 20 keypoints allow ~55).
const std::string kSmall =
    " --set surf.width=512 --set surf.height=384 --set surf.target_keypoints=20 --set surf.frames=4";

nlohmann::json verdict(const std::string& name, const std::string& sets, int expected_exit) {
    const std::string out = fresh_dir(name);
    const auto r = surfvp("run " + kBudget + " --trace none --quiet --out " + out + kSmall + " " + sets);
    EXPECT_EQ(r.exit_code, expected_exit) << r.err;
    return nlohmann::json::parse(slurp(out + "/report.json"));
}

double fps_at(const std::string& name, const std::string& sets) {
    const std::string out = fresh_dir(name);
    const auto r =
        surfvp("run " + kBudget + " --trace none --quiet --out " + out + kSmall + test::kOneRun + " " + sets);
    EXPECT_LE(r.exit_code, 1) << r.err;
    return nlohmann::json::parse(slurp(out + "/report.json"))["throughput_fps"].get<double>();
}

TEST(Verdict, BreakEvenClockIsTheEdgeOfTheBudget) {
    const auto r = verdict("break_even", "--set budget.fps=40 --set verdict.band=off", 1);
    const auto& v = r["verdict"];
    EXPECT_FALSE(v["met"].get<bool>());
    EXPECT_NEAR(v["margin"].get<double>(), r["throughput_fps"].get<double>() / 40 - 1, 1e-12);
    EXPECT_EQ(v["limit"]["resource"], "fhg");
    ASSERT_EQ(v["break_even"].size(), 2u);
    const auto& clock = v["break_even"][0];
    EXPECT_EQ(clock["parameter"], "fhg.clock");
    EXPECT_TRUE(clock["check"]["met"].get<bool>()) << clock;
    EXPECT_GE(clock["fps"].get<double>(), 40.0);
    // The answer meets the budget and 0.3 % less does not: it is the edge, not just a value that works.
    const double hz = std::stod(clock["value"].get<std::string>()) * 1e6;
    EXPECT_GE(fps_at("at_edge", fmt::format("--set 'fhg.clock={:.3f} MHz'", hz / 1e6)), 40.0);
    EXPECT_LT(fps_at("below_edge", fmt::format("--set 'fhg.clock={:.3f} MHz'", hz * 0.997 / 1e6)), 40.0);
    const auto& cycles = v["break_even"][1];
    EXPECT_EQ(cycles["parameter"], "fhg.cycles_per_block");
    const int c = std::stoi(cycles["value"].get<std::string>());
    EXPECT_GE(fps_at("cycles_edge", fmt::format("--set 'fhg.cycles_per_block={} cycles'", c)), 40.0);
    EXPECT_LT(fps_at("cycles_over", fmt::format("--set 'fhg.cycles_per_block={} cycles'", c + 1)), 40.0);
    EXPECT_NE(v["statement"].get<std::string>().find("missed at defaults"), std::string::npos);
}

// Met at the defaults, the break-even says how far the clock may fall.
TEST(Verdict, BreakEvenWhenMetIsHowLowTheClockMayGo) {
    const auto r = verdict("met", "--set budget.fps=20 --set verdict.band=off", 0);
    const auto& clock = r["verdict"]["break_even"][0];
    EXPECT_LT(std::stod(clock["value"].get<std::string>()), 100.0);
    EXPECT_NE(r["verdict"]["statement"].get<std::string>().find("met at defaults"), std::string::npos);
}

TEST(Verdict, BandReSimulatesEveryAssumptionAndNamesWhatFlipsIt) {
    const std::string out = fresh_dir("band");
    const auto run = surfvp("run " + kBudget + " --trace none --quiet --out " + out + kSmall +
                            " --set budget.fps=40 --set verdict.break_even=off --set verdict.samples=20");
    ASSERT_LE(run.exit_code, 1) << run.err;
    const auto r = nlohmann::json::parse(slurp(out + "/report.json"));
    const auto& band = r["verdict"]["band"];
    EXPECT_EQ(band["frames"], 2);
    EXPECT_GT(band["axes"].size(), 40u);  // the unknowns; design choices and the workload are in "changes"
    const double ref = band["reference_fps"].get<double>(), run_fps = r["throughput_fps"].get<double>();
    EXPECT_NEAR(ref, run_fps, 1e-3 * ref);  // 2 frames are the steady state here
    EXPECT_EQ(band["run_fps"].get<double>(), run_fps);
    EXPECT_LE(band["low_fps"].get<double>(), run_fps);
    EXPECT_GE(band["high_fps"].get<double>(), run_fps);
    // Each flip is a point on the other side of the budget from the reference, and every such
    // point is listed.
    size_t flips = 0;
    for (const auto& a : band["axes"])
        for (const char* side : {"low", "high"}) {
            const auto& s = a[side];
            if (!s.contains("fps") || s["fps"].is_null()) continue;
            // A point's rate is the run's plus its effect against the reference.
            EXPECT_NEAR(s["fps"].get<double>(), run_fps + s["point_fps"].get<double>() - ref, 1e-9);
            const bool other_side = (s["fps"].get<double>() >= 40) != (run_fps >= 40);
            flips += other_side;
            const std::string name = a["parameter"].get<std::string>() + " = " + s["value"].get<std::string>();
            const bool listed =
                std::find(band["flipping"].begin(), band["flipping"].end(), name) != band["flipping"].end();
            EXPECT_EQ(other_side, listed) << name;
        }
    EXPECT_GT(flips, 0u) << "the FHG clock's high alone crosses 40 frames/s from 38.4";
    // Exact Haar wavelets (a software design choice) make the CPU the limit.
    for (const auto& a : r["verdict"]["changes"]["axes"]) {
        if (a["parameter"] == "surf.haar") {
            EXPECT_EQ(a["low"]["limit"], "cpu") << a;
        }
    }
    EXPECT_EQ(band["failed_points"].size(), 0u) << band["failed_points"];
    const std::string svg = slurp(out + "/tornado.svg");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("fhg.clock"), std::string::npos);
    EXPECT_EQ(svg.find("surf.haar"), std::string::npos);  // not an unknown
    EXPECT_NE(svg.find("budget 40"), std::string::npos);
    const std::string md = slurp(out + "/report.md");
    EXPECT_NE(md.find("## Verdict"), std::string::npos);
    EXPECT_NE(md.find("![tornado](tornado.svg)"), std::string::npos);
}

// The verdict does not depend on how many re-simulations run at once.
TEST(Verdict, JobsDoNotChangeTheVerdict) {
    const std::string sets = "--set budget.fps=40 --set verdict.band=off";
    auto one = verdict("one_job", sets + " --set verdict.jobs=1", 1)["verdict"];
    auto two = verdict("two_jobs", sets + " --set verdict.jobs=2", 1)["verdict"];
    EXPECT_EQ(one.dump(), two.dump());
}

// The band splits by role: the unknowns one at a time (the tornado) and jointly, design choices
// and the workload apart, as what a review can change.
TEST(Verdict, TheDoubtIsTheUnknownsJointlyAndTheChangesApart) {
    const auto r = verdict("doubt",
                           "--set budget.fps=40 --set verdict.break_even=off --set verdict.software=off "
                           "--set verdict.samples=40",
                           1);
    const auto& v = r["verdict"];
    std::set<std::string> unknown, change;
    for (const auto& a : v["band"]["axes"]) unknown.insert(a["parameter"].get<std::string>());
    for (const auto& a : v["changes"]["axes"]) change.insert(a["parameter"].get<std::string>());
    EXPECT_TRUE(unknown.count("fhg.clock") && unknown.count("fhg.line_fifo") && unknown.count("apu.overlap"));
    EXPECT_TRUE(change.count("fhg.bus_word") && change.count("surf.haar") && change.count("surf.target_keypoints"));
    for (const auto& key : change) EXPECT_FALSE(unknown.count(key)) << key;
    const auto& d = v["doubt"];
    EXPECT_EQ(d["points"], 40);
    EXPECT_EQ(d["failed_points"].size(), 0u) << d["failed_points"];
    EXPECT_LE(d["fps"]["p5"].get<double>(), d["fps"]["p50"].get<double>());
    EXPECT_LE(d["fps"]["p50"].get<double>(), d["fps"]["p95"].get<double>());
    EXPECT_GE(d["probability_met"].get<double>(), 0.0);
    EXPECT_LE(d["probability_met"].get<double>(), 1.0);
    EXPECT_EQ(d["sensitivity"].size(), d["unknowns"].get<size_t>());
    for (const auto& s : d["sensitivity"]) EXPECT_TRUE(unknown.count(s["parameter"].get<std::string>())) << s;
    EXPECT_NE(v["statement"].get<std::string>().find("over the unknowns jointly"), std::string::npos) << v["statement"];
    const std::string md = slurp(fresh_path("doubt") + "/report.md");
    EXPECT_NE(md.find("The doubt, jointly"), std::string::npos);
    EXPECT_NE(md.find("What a review can change"), std::string::npos);
}

// The chain of limits: the FHG first, relieved at its break-even; then the CPU, named with its
// headroom, its clock searched down to where the rate starts to fall.
TEST(Verdict, TheChainRelievesEachLimitAndNamesTheNext) {
    const auto r = verdict("chain", "--set budget.fps=40 --set verdict.band=off --set verdict.software=off", 1);
    const auto& chain = r["verdict"]["chain"];
    ASSERT_GE(chain.size(), 2u) << chain;
    EXPECT_EQ(chain[0]["resource"], "fhg");
    EXPECT_LT(chain[0]["headroom"].get<double>(), 0.0);
    EXPECT_EQ(chain[0]["break_even"], r["verdict"]["break_even"]);
    EXPECT_EQ(chain[1]["resource"], "cpu");
    EXPECT_GT(chain[1]["headroom"].get<double>(), 0.0);
    ASSERT_EQ(chain[1]["relieved"].size(), 1u);
    EXPECT_EQ(chain[1]["relieved"][0]["parameter"], "fhg.clock");
    EXPECT_EQ(chain[1]["relieved"][0]["value"], chain[0]["break_even"][0]["value"]);
    const auto& cpu = chain[1]["break_even"][0];
    EXPECT_EQ(cpu["parameter"], "cpu.clock");
    EXPECT_EQ(cpu["searched"], "down");
    EXPECT_LT(std::stod(cpu["value"].get<std::string>()), 400.0);
    for (const auto& step : chain)
        for (const auto& b : step["break_even"])
            if (!b["value"].is_null()) {
                EXPECT_TRUE(b["check"]["met"].get<bool>()) << b;
            }
    EXPECT_NE(slurp(fresh_path("chain") + "/report.md").find("**down to "), std::string::npos);
}

// A CPU stalled (a blocking cache) on memory latency is not relieved by its clock: the search goes to the
// latency, down, and its value passes the whole run's check.
TEST(Verdict, ACpuStalledOnFillsIsRelievedByTheMemory) {
    const auto r = verdict(
        "stalled",
        "--set budget.fps=30 --set 'memory.latency=400 cycles' --set cpu.outstanding_fills=1 --set verdict.band=off "
        "--set verdict.software=off",
        1);
    const auto& first = r["verdict"]["chain"][0];
    EXPECT_EQ(first["resource"], "cpu") << first;
    std::map<std::string, nlohmann::json> by;
    for (const auto& b : first["break_even"]) by[b["parameter"].get<std::string>()] = b;
    ASSERT_TRUE(by.count("memory.latency")) << first;
    const auto& latency = by["memory.latency"];
    ASSERT_FALSE(latency["value"].is_null()) << latency;
    EXPECT_EQ(latency["searched"], "down");
    EXPECT_LT(std::stoi(latency["value"].get<std::string>()), 400);
    EXPECT_TRUE(latency["check"]["met"].get<bool>()) << latency;
}

// The software settings the CPU's time rests on, each re-simulated: exact wavelets cost more
// CPU time than rounded ones, U-SURF less, M-SURF more, and CPU time grows with the keypoints
// per frame.
TEST(Verdict, SoftwareSettingsSayWhatTheCpuTimeRestsOn) {
    const auto r = verdict("software", "--set verdict.band=off --set verdict.break_even=off", 0);
    std::map<std::string, double> cpu_ms;
    for (const auto& row : r["verdict"]["software"]) {
        ASSERT_FALSE(row.contains("error")) << row;
        cpu_ms[row["setting"].get<std::string>()] = row["cpu_ms_per_frame"].get<double>();
        EXPECT_GT(row["fps"].get<double>(), 0.0) << row;
    }
    ASSERT_EQ(cpu_ms.size(),
              9u);  // the scenario (20 keypoints), the double FPU, exact Haar, upright, M-SURF, 50 ... 200 keypoints
    const double base = cpu_ms["as the scenario"];
    EXPECT_GT(cpu_ms["fpu.precision = double"], 1.2 * base);
    EXPECT_GT(cpu_ms["surf.haar = exact"], 2.5 * base);
    EXPECT_LT(cpu_ms["surf.upright = on"], 0.8 * base);
    EXPECT_GT(cpu_ms["surf.descriptor = msurf"], 1.15 * base);  // 1.5 times Bay's descriptor, ~60 % of the work
    EXPECT_LT(cpu_ms["surf.target_keypoints = 50"], cpu_ms["surf.target_keypoints = 100"]);
    EXPECT_LT(cpu_ms["surf.target_keypoints = 100"], cpu_ms["surf.target_keypoints = 150"]);
    const std::string md = slurp(fresh_path("software") + "/report.md");
    EXPECT_NE(md.find("Settings the CPU's time rests on"), std::string::npos);
    EXPECT_NE(md.find("FPU: the single-precision APU FPU"), std::string::npos);
    EXPECT_NE(md.find("| surf.haar = exact |"), std::string::npos);
}

}  // namespace
}  // namespace surfvp
