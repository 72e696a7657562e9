// Frames of different sizes in one run (a list of images): each task is programmed with its
// own frame's size, the buffers fit the largest, and each frame's keypoints are those a run of
// that image alone gives; an image the chip cannot take is named.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli.h"

namespace surfvp {
namespace {
using nlohmann::json;
using test::fresh_dir;
using test::slurp;
using test::surfvp;

const std::string kCastleScenario = std::string(SURFVP_SOURCE_DIR) + "/scenarios/castle_sequence.yaml";
// A fixed threshold: a run of one image alone would calibrate on that image.
const std::string kFixed = " --set eval.poses= --set surf.target_keypoints=0 --set surf.threshold=60";
const std::string kRun = " --quiet --trace none";

std::string castle(int n) { return test::kCastle + "/Images/Image_000" + std::to_string(n) + ".pgm"; }

TEST(FrameSizes, ImagesOfDifferentSizesGoThroughOneRunEachAsAlone) {
    REQUIRE_CASTLE();
    REQUIRE_OPENCV_DATA("graf3.png");
    const std::string dir = fresh_dir("sizes");
    const std::string list = test::write_file(
        dir, "mixed.txt", castle(1) + "\n" + test::graf(1) + "\n" + castle(2) + "\n" + test::graf(3) + "\n");
    const std::string sets = kRun + kFixed + " --set surf.frames=4 --set surf.source=" + list;
    const auto vp = surfvp("run " + kCastleScenario + sets + " --out " + dir + "/vp");
    ASSERT_EQ(vp.exit_code, 0) << vp.err;
    const json r = json::parse(slurp(dir + "/vp/report.json"));
    EXPECT_EQ(r["frame_sizes"], json::array({"640x480", "800x640"}));
    EXPECT_EQ(r["image"]["width"], 640);  // frame 0's
    ASSERT_EQ(surfvp("run " + kCastleScenario + sets + " --direct --out " + dir + "/direct").exit_code, 0);
    for (const auto& [frame, image] : {std::pair{1, test::graf(1)}, std::pair{2, castle(2)}}) {
        const std::string alone = dir + "/alone" + std::to_string(frame);
        ASSERT_EQ(surfvp("run " + kCastleScenario + kRun + kFixed + " --set surf.frames=2 --set surf.source=" + image +
                         " --out " + alone)
                      .exit_code,
                  0);
        const std::string f = "/keypoints/frame_000" + std::to_string(frame) + ".surf";
        const std::string kept = slurp(dir + "/vp" + f);
        EXPECT_GT(kept.size(), 1000u) << f;
        EXPECT_EQ(kept, slurp(alone + "/keypoints/frame_0000.surf")) << image;
        EXPECT_EQ(kept, slurp(dir + "/direct" + f)) << f;
    }
}

TEST(FrameSizes, AnImageTheChipCannotTakeIsNamed) {
    REQUIRE_CASTLE();
    REQUIRE_OPENCV_DATA("graf1.png");
    const std::string dir = fresh_dir("too_wide");
    const std::string list = test::write_file(dir, "mixed.txt", castle(1) + "\n" + test::graf(1) + "\n");
    const auto r = surfvp("validate " + kCastleScenario + kFixed +
                          " --set surf.frames=2 --set iig.max_width=700 --set surf.source=" + list);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(
        r.err.find("frame 1 (" + test::graf(1) + ") of 800x640 is larger than the chip takes: iig.max_width is 700"),
        std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace surfvp
