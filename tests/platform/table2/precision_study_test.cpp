// `surfvp precision`: a width narrowed too far drops the Table II rows measurably, one that
// still holds every sum gives the very same keypoints, and the report names the fewest bits.
#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli.h"

namespace surfvp {
namespace {
using nlohmann::json;
using test::fresh_dir;
using test::slurp;
using test::surfvp;

TEST(PrecisionStudy, TooFewBitsDropTheRowsAndTheReportNamesTheFewest) {
    REQUIRE_CASTLE();
    REQUIRE_OPENCV_DATA("graf3.png");
    const std::string out = fresh_dir("precision");
    const auto r = surfvp(
        "precision castle_sequence --pair graf --quiet --set surf.frames=8 --axis 'fhg.response_bits=8 bit' "
        "--axis 'fhg.accumulator_bits=22 bit' --out " +
        out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json report = json::parse(slurp(out + "/report.json"));
    ASSERT_TRUE(report["full_precision"].contains("rounded"));
    const json& points = report["points"];
    ASSERT_EQ(points.size(), 4u);  // the scenario's widths, two narrowed, and the fewest together
    const json &base = points[0]["result"], &response8 = points[1]["result"], &accumulator22 = points[2]["result"];
    EXPECT_TRUE(base["within"].get<bool>());
    // 8-bit responses saturate: every row drops (measured -0.019 to -0.032 on 8 frames).
    EXPECT_FALSE(response8["within"].get<bool>());
    EXPECT_LT(response8["worst_change"].get<double>(), -0.015);
    // A 22-bit accumulator still holds every sum of these frames: the same keypoints, fewer LUTs.
    EXPECT_EQ(accumulator22["ransac"], base["ransac"]);
    EXPECT_EQ(accumulator22["pair"], base["pair"]);
    EXPECT_LT(accumulator22["luts"].get<double>(), base["luts"].get<double>());
    EXPECT_EQ(accumulator22["det_bytes_per_frame"], base["det_bytes_per_frame"]);
    // The fewest bits: the narrowed accumulator holds, the 8-bit responses do not.
    ASSERT_EQ(report["fewest_bits"].size(), 2u);
    EXPECT_EQ(report["fewest_bits"][0]["key"], "fhg.response_bits");
    EXPECT_EQ(report["fewest_bits"][0]["fewest"], "18 bit");
    EXPECT_EQ(report["fewest_bits"][1]["fewest"], "22 bit");
    EXPECT_TRUE(report["all_fewest_together"]["result"]["within"].get<bool>());
    EXPECT_NE(slurp(out + "/report.md").find("| fhg.accumulator_bits | 22 bit | 24 bit |"), std::string::npos);
    EXPECT_NE(slurp(out + "/precision.svg").find("fhg.response_bits"), std::string::npos);
    const std::string csv = slurp(out + "/results.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);  // a header and the four points
}

// A chip run that broke makes a point's row no measurement: exit 6; one that missed a goal: 1.
TEST(PrecisionStudy, AChipRunThatMissesAGoalOrBreaksHasItsExitCode) {
    REQUIRE_CASTLE();
    const std::string out = fresh_dir("precision_exit");
    const std::string study =
        "precision castle_sequence --quiet --set surf.frames=3 --axis 'fhg.accumulator_bits=22 bit' ";
    const auto missed = surfvp(study + "--set surf.target_keypoints=100000 --out " + out);
    EXPECT_EQ(missed.exit_code, 1) << missed.err;
    const auto broken = surfvp(study + "--set fhg.maxima_fifo_depth=4 --out " + out);
    EXPECT_EQ(broken.exit_code, 6) << broken.err;
    const json report = json::parse(slurp(out + "/report.json"));
    EXPECT_EQ(report["points"][0]["result"]["chip_run_exit"], 6);
}

TEST(PrecisionStudy, BadAxesAndPairsAreRefusedBeforeAnyPointRuns) {
    REQUIRE_CASTLE();
    const std::string out = test::fresh_path("precision_bad");
    std::filesystem::remove_all(out);
    for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
             {"--axis 'fhg.nope=3 bit'", "fhg.nope"},
             {"--axis fhg.det_bits", "give KEY=VALUE,VALUE"},
             {"--axis 'fhg.det_bits=40 bit'", "--axis fhg.det_bits=40 bit"},
             {"--pair castle_sequence", "it has none"},
             {"--axis 'faults=[]'", "'faults' is not a parameter"},  // once a SIGSEGV after every point ran
             {"--axis 'fhg.det_bits=24 bit,'", "value 2 is empty"},
             {"--axis 'fhg.det_bits=, 20 bit'", "value 1 is empty"},
             {"--pair faults", "faults.yaml:15: faults: the precision study runs the chip without time"},
             {"--set surf.frames=0", "surf.frames"},
             {"--axis 'fhg.det_frac_bits=40 bit'", "det_frac_bits must not exceed 2 x response_frac_bits"},
             {"--axis 'fhg.det_bits=24 bit' --axis 'fhg.det_bits=20 bit'", "has an --axis already"}}) {
        const auto r = surfvp("precision castle_sequence " + args + " --out " + out);
        EXPECT_EQ(r.exit_code, 2) << args;
        EXPECT_NE(r.err.find(says), std::string::npos) << args << ": " << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace surfvp
