// surfvp compare and run --compare-to (docs/compare.md): the parameters that differ, each
// figure with its change against the first side, the budgets each meets; run folders and sweep
// points alike; a side that is neither is bad input.
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli.h"

namespace surfvp::test {
namespace {
using Json = nlohmann::json;

const std::string kSmall = kOneRun +
                           " --trace none --quiet --set surf.frames=3 --set surf.width=256 --set surf.height=192"
                           " --set surf.target_keypoints=20 --set budget.fps=40";

TEST(Compare, ARunAgainstAnEarlierOneGivesEachFigureItsChange) {
    const std::string a = fresh_dir("cmp_a"), b = fresh_dir("cmp_b");
    ASSERT_EQ(surfvp("run " + kBudget + kSmall + " --set fhg.clock=25MHz --out " + a).exit_code,
              1);  // misses 40 frames/s
    const auto r = surfvp("run " + kBudget + kSmall + " --set 'fhg.clock=50 MHz' --out " + b + " --compare-to " + a);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json c = Json::parse(slurp(b + "/compare.json"));
    EXPECT_EQ(c["sides"][1]["name"], b);
    ASSERT_EQ(c["parameters"].size(), 1u) << c["parameters"];
    EXPECT_EQ(c["parameters"]["fhg.clock"], (Json{"25MHz", "50 MHz"}));
    const auto& fps = c["figures"]["fps"];
    const double before = fps[0]["value"], after = fps[1]["value"];
    EXPECT_DOUBLE_EQ(fps[1]["delta"].get<double>(), after - before);
    EXPECT_DOUBLE_EQ(fps[1]["percent"].get<double>(), 100 * (after - before) / before);
    EXPECT_GT(after, 1.5 * before);
    EXPECT_EQ(c["budgets"][0]["frame_rate"], false);
    EXPECT_EQ(c["budgets"][1]["frame_rate"], true);
    EXPECT_EQ(c["budgets"][1]["fits_fpga"], true);
    EXPECT_TRUE(c["other_figures"].contains("fhg.busy_s")) << c["other_figures"].size();
    EXPECT_FALSE(c["other_figures"].contains("wall_time_s"));  // wall clock is not a figure of the chip
    const std::string md = slurp(b + "/compare.md");
    EXPECT_NE(md.find("| fhg.clock | 25MHz | 50 MHz |"), std::string::npos) << md.substr(0, 800);
    EXPECT_NE(md.find("| frame_rate | **missed** | met |"), std::string::npos) << md.substr(0, 800);
    // Figures through their units: frames/s, shares in percent with changes in points, times in ms.
    EXPECT_EQ(c["figure_units"]["fps"], "frames/s");
    EXPECT_EQ(c["figure_units"]["busy.fhg"], "share");
    EXPECT_NE(md.find(fmt::format("| fps | {:.4g} frames/s | {:.4g} frames/s (+", before, after)), std::string::npos)
        << md;
    EXPECT_NE(md.find(fmt::format("| busy.fhg | {:.1f} % |", 100 * c["figures"]["busy.fhg"][0]["value"].get<double>())),
              std::string::npos)
        << md;
    EXPECT_NE(md.find(" points) |"), std::string::npos) << md;
    EXPECT_EQ(md.find("| busy.fhg | 0."), std::string::npos) << md;
}

// A parameter whose 0 stands for something says what, and what the run made of it.
TEST(Compare, AParameterAtItsSentinelShowsItsEffectiveValue) {
    const std::string a = fresh_dir("cmp_sentinel_a"), b = fresh_dir("cmp_sentinel_b");
    ASSERT_LE(surfvp("run " + kBudget + kSmall + " --out " + a).exit_code, 1);
    ASSERT_LE(surfvp("run " + kBudget + kSmall + " --set 'fhg.cycles_per_block=40 cycles' --out " + b).exit_code, 1);
    const Json report = Json::parse(slurp(a + "/report.json"));
    const auto r = surfvp("compare " + a + " " + b);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(fmt::format("| fhg.cycles_per_block | 0 cycles (the sequence's: {} cycles) | 40 cycles |",
                                     report["fhg"]["cycles_per_block"].get<int>())),
              std::string::npos)
        << r.out;
}

TEST(Compare, SweepPointsSideBySide) {
    const std::string dir = fresh_dir("cmp_sweep");
    const std::string file = write_file(dir, "s.yaml",
                                        "scenario: " + kBudget +
                                            "\nset: {surf.frames: 3, surf.width: 256, surf.height: 192}\n"
                                            "axes:\n  fhg.clock: [25 MHz, 100 MHz]\n");
    ASSERT_EQ(surfvp("sweep " + file + " --quiet --out " + dir + "/out").exit_code, 0);
    const auto r = surfvp("compare " + dir + "/out@0 " + dir + "/out@1 --json " + dir + "/c.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json c = Json::parse(slurp(dir + "/c.json"));
    EXPECT_EQ(c["parameters"], (Json{{"fhg.clock", {"25 MHz", "100 MHz"}}}));
    EXPECT_GT(c["figures"]["fps"][1]["percent"].get<double>(), 0.0);
    EXPECT_NE(r.out.find("## Figures"), std::string::npos) << r.out;
}

TEST(Compare, ASideThatIsNoRunIsBadInput) {
    const std::string dir = fresh_dir("cmp_bad");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"compare " + dir, "give two or more"},
        {"compare " + dir + "/none " + dir, "not a run folder nor SWEEP_DIR@POINT"},
        {"compare " + dir + " " + dir, "no report.json"},
        {"compare " + dir + "@3 " + dir, "no results.json"},
    };
    for (const auto& [args, message] : cases) {
        const auto r = surfvp(args);
        EXPECT_EQ(r.exit_code, 2) << args;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    }
    const std::string out = dir + "/never";
    const auto run = surfvp("run " + kBudget + kSmall + " --out " + out + " --compare-to " + dir + "/none");
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_FALSE(std::filesystem::exists(out));  // refused before anything is simulated or written
}

// What compare reads is someone else's folder: damaged, foreign or hostile content is bad
// input naming the file, never a crash (each case once ended in SIGSEGV or exit 3).
TEST(Compare, DamagedOrHostileSidesAreBadInputNamingTheFile) {
    const std::string dir = fresh_dir("cmp_hostile");
    const auto side = [&](const std::string& name, const std::string& file, const std::string& text) {
        std::filesystem::create_directories(dir + "/" + name);
        write_file(dir + "/" + name, file, text);
        return dir + "/" + name;
    };
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    const std::vector<std::pair<std::string, std::string>> cases = {
        {side("no_points", "results.json", "{\"sweep\": \"x\"}") + "@0", "has no list of points"},
        {side("points_not_list", "results.json", "{\"points\": 7}") + "@0", "has no list of points"},
        {side("huge_point", "results.json", "{\"points\": []}") + "@99999999999999999999", "no sweep has point"},
        {side("deep_results", "results.json", "{\"points\": " + deep + "}") + "@0", "nested deeper than 64 levels"},
        {side("deep_report", "report.json", "{\"a\": " + deep + "}"), "nested deeper than 64 levels"},
        {side("not_json", "report.json", "{\"a\": 1,"), "not valid JSON"},
        {side("array_report", "report.json", "[1, 2]"), "is not a JSON object"},
    };
    const std::string good = side("good", "report.json", "{\"fps\": 1}");
    for (const auto& [bad, message] : cases) {
        const auto r = surfvp("compare " + good + " " + bad);
        EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << bad << ": " << r.err;
        EXPECT_NE(r.err.find(dir), std::string::npos) << bad << ": " << r.err;
    }
    // Mistyped values are absent, not errors: a point whose fields are of other types compares.
    const std::string odd = side("odd_point", "results.json",
                                 "{\"points\": [{\"point\": \"0\"}, {\"point\": 0, \"params\": 3, \"figures\": "
                                 "{\"budget_met\": \"yes\", \"fps\": 2}}], \"wall_clock_fields\": [1, {}]}");
    side("odd_run", "report.json", "{\"fps\": 1, \"wall_clock_fields\": [1, null], \"budget_met\": 3}");
    write_file(dir + "/odd_run", "config.yaml", "- not\n- a map\n");
    const auto r = surfvp("compare " + odd + "@0 " + dir + "/odd_run");
    EXPECT_EQ(r.exit_code, 2) << r.err;  // config.yaml is a list
    EXPECT_NE(r.err.find("config.yaml: a configuration is a map of sections"), std::string::npos) << r.err;
    std::filesystem::remove(dir + "/odd_run/config.yaml");
    const auto fine = surfvp("compare " + odd + "@0 " + dir + "/odd_run --json " + dir + "/c.json");
    EXPECT_EQ(fine.exit_code, 0) << fine.err;
}

}  // namespace
}  // namespace surfvp::test
