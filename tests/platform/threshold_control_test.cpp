// libSSA2's keypoint-count control (surf.threshold_control = track) on the castle: each frame's
// THRESHOLD follows from the count of the frame `tasks in flight` before it, the VP and direct
// mode agree byte for byte, the count stays nearer the target than with the held threshold,
// and config.yaml and report.md say what was used.
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli.h"

namespace surfvp {
namespace {
using nlohmann::json;
using test::fresh_dir;
using test::slurp;
using test::surfvp;

json run(const std::string& out, const std::string& sets) {
    const auto r = surfvp("run castle_sequence --quiet --trace none --out " + out + sets);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(slurp(out + "/report.json"));
}

double spread_from(const json& per_frame, double target) {
    double sum = 0;
    for (const json& f : per_frame) sum += std::abs(f["keypoints"].get<double>() - target);
    return sum / double(per_frame.size());
}

TEST(ThresholdControl, EachFrameLearnsFromTheFrameTwoBeforeInTheVpAndDirectModeAlike) {
    REQUIRE_CASTLE();
    const std::string track = fresh_dir("track"), direct = fresh_dir("track_direct"), hold = fresh_dir("hold");
    const json r = run(track, " --set surf.threshold_control=track");
    const json frames = r["workload"]["per_frame"];
    ASSERT_EQ(frames.size(), 40u);
    const double first = frames[0]["threshold"];
    EXPECT_NEAR(first, r["threshold"].get<double>(), 1.0 / 65536);  // the calibrated one, as the register holds it
    EXPECT_EQ(frames[1]["threshold"].get<double>(), first);         // two buffer sets: nothing reported yet
    for (size_t n = 2; n < frames.size(); ++n) {
        const double before = frames[n - 2]["threshold"], now = frames[n]["threshold"];
        const double step = std::clamp(std::sqrt(frames[n - 2]["keypoints"].get<double>() / 100), 0.5, 2.0);
        EXPECT_NEAR(now, before * step, 1.0 / 65536) << "frame " << n;  // to the register's last bit
    }
    // Timing plays no part: direct mode gives the same keypoints.
    ASSERT_EQ(
        surfvp("run castle_sequence --quiet --direct --set surf.threshold_control=track --out " + direct).exit_code, 0);
    for (int i = 0; i < 40; i += 3) {
        const std::string f = fmt::format("/keypoints/frame_{:04}.surf", i);
        EXPECT_EQ(slurp(track + f), slurp(direct + f)) << f;
    }
    // The held threshold drifts to ~130 keypoints on the castle; tracking holds ~100.
    const json held = run(hold, "");
    EXPECT_LT(spread_from(frames, 100), 0.75 * spread_from(held["workload"]["per_frame"], 100));
    EXPECT_NEAR(r["keypoints_per_frame"].get<double>(), 100, 10);
    // What was used, where a reader looks.
    EXPECT_NE(slurp(track + "/config.yaml").find("threshold: 500  # default"), std::string::npos);
    EXPECT_NE(slurp(track + "/config.yaml").find("not used: 63.3354 instead"), std::string::npos);
    EXPECT_NE(slurp(track + "/report.md").find("threshold per frame"), std::string::npos);
    EXPECT_NE(slurp(track + "/frames.csv").find(",threshold\n"), std::string::npos);
}

TEST(ThresholdControl, TrackingNeedsATarget) {
    const auto r = surfvp("validate castle_sequence --set surf.threshold_control=track --set surf.target_keypoints=0");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(
                  "surf.threshold_control: track holds the keypoints per frame near surf.target_keypoints, which is 0"),
              std::string::npos)
        << r.err;
}

// A target the image cannot give is said, not passed over: the calibration's threshold is
// then 0 (every maximum), and the run fails that check.
TEST(ThresholdControl, AnUnreachableTargetIsAFailedCheck) {
    REQUIRE_CASTLE();
    const std::string out = fresh_dir("unreachable");
    const auto r = surfvp(
        "run castle_sequence --quiet --trace none --direct --set surf.frames=2 --set surf.target_keypoints=50000 "
        "--out " +
        out);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    const json report = json::parse(slurp(out + "/report.json"));
    bool found = false;
    for (const json& c : report["checks"])
        if (c["name"] == "keypoint target reachable") {
            found = true;
            EXPECT_FALSE(c["passed"].get<bool>());
            EXPECT_NE(c["detail"].get<std::string>().find("not more than surf.target_keypoints = 50000"),
                      std::string::npos);
        }
    EXPECT_TRUE(found);
    EXPECT_EQ(report["threshold"].get<double>(), 0.0);
}

}  // namespace
}  // namespace surfvp
