// `surfvp surf`, `eval`, `eval-seq` and `draw` end to end on real images: the Graffiti pair
// and vtest.avi of opencv-doc, the simulated castle of visp-images-data. Missing data fails
// the test with the package's name; nothing is skipped.
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <regex>
#include <sstream>

#include "cli.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using test::fresh_dir;
using test::slurp;
using test::surfvp;
using test::write_file;

using test::kCastle;
using test::kOpencvData;

// A keypoint file as the Mikolajczyk format writes it: dimension, count, then one line of
// x y a b c [sign] d1..d64 per keypoint. Each line's value count is checked.
struct KeypointFileText {
    int dimension = 0;
    std::size_t count = 0;
    std::vector<std::vector<double>> rows;
};

KeypointFileText parse_keypoint_file(const std::string& path) {
    std::istringstream in(slurp(path));
    KeypointFileText file;
    in >> file.dimension >> file.count;
    std::string line;
    std::getline(in, line);  // rest of the count's line
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::istringstream values(line);
        std::vector<double> row;
        for (double v; values >> v;) row.push_back(v);
        file.rows.push_back(row);
    }
    return file;
}

// "N keypoints, threshold T, X ms" on stderr.
struct SurfSummary {
    std::size_t keypoints;
    std::string threshold;  // as printed (%.9g round-trips the float)
};

SurfSummary surf_summary(const std::string& err) {
    std::smatch m;
    const std::regex line(R"(^(\d+) keypoints, threshold ([0-9.e+-]+), [0-9.]+ ms\n)");
    if (!std::regex_search(err, m, line)) {
        ADD_FAILURE() << "no summary line in: " << err;
        return {0, ""};
    }
    return {std::stoul(m[1]), m[2]};
}

TEST(QualityCli, SurfWritesExactlyTheTargetCount) {
    REQUIRE_OPENCV_DATA("graf1.png");
    const std::string dir = fresh_dir("surf_count");
    const auto r = surfvp("surf " + test::graf(1) + " --target-count 500 --out " + dir + "/g1.key");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const SurfSummary summary = surf_summary(r.err);
    EXPECT_EQ(summary.keypoints, 500u);
    const KeypointFileText file = parse_keypoint_file(dir + "/g1.key");
    EXPECT_EQ(file.dimension, 65);
    EXPECT_EQ(file.count, 500u);
    ASSERT_EQ(file.rows.size(), 500u);
    for (const auto& row : file.rows) {
        ASSERT_EQ(row.size(), 2u + 3u + 65u);
        EXPECT_TRUE(row[5] == 1 || row[5] == -1) << "Laplacian sign";
    }
    EXPECT_TRUE(fs::exists(dir + "/g1.key.meta"));

    // The threshold it printed gives the same keypoints; --no-laplacian drops the sign column.
    const auto again = surfvp("surf " + test::graf(1) + " --threshold " + summary.threshold +
                              " --no-laplacian -q --out " + dir + "/again.key");
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(again.err, "") << "--quiet";
    const KeypointFileText same = parse_keypoint_file(dir + "/again.key");
    EXPECT_EQ(same.dimension, 64);
    ASSERT_EQ(same.rows.size(), 500u);
    EXPECT_EQ(same.rows.front()[0], file.rows.front()[0]);
    EXPECT_EQ(same.rows.back()[1], file.rows.back()[1]);
}

TEST(QualityCli, SurfThresholdAndTargetCountExcludeEachOther) {
    REQUIRE_OPENCV_DATA("graf1.png");
    const std::string dir = fresh_dir("surf_excludes");
    const auto r = surfvp("surf " + test::graf(1) + " --threshold 30 --target-count 100 --out " + dir + "/x.key");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/x.key"));
}

TEST(QualityCli, SurfOnAMissingImageNamesIt) {
    const std::string dir = fresh_dir("surf_missing");
    const auto r = surfvp("surf " + dir + "/no_such.png --out " + dir + "/x.key");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("surfvp: error: " + dir + "/no_such.png: file does not exist"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/x.key"));
}

TEST(QualityCli, SurfOnATooSmallImageSaysWhy) {
    const std::string dir = fresh_dir("surf_small");
    ASSERT_TRUE(cv::imwrite(dir + "/small.png", cv::Mat(20, 40, CV_8UC1, cv::Scalar(128))));
    const auto r = surfvp("surf " + dir + "/small.png --out " + dir + "/x.key");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(dir + "/small.png: image 40x20 is too small"), std::string::npos) << r.err;
}

TEST(QualityCli, EvalOfAFileWithItselfIsPerfect) {
    REQUIRE_OPENCV_DATA("graf1.png");
    const std::string dir = fresh_dir("eval_self");
    ASSERT_EQ(surfvp("surf " + test::graf(1) + " --target-count 300 -q --out " + dir + "/g1.key").exit_code, 0);
    const std::string identity = write_file(dir, "identity.txt", "1 0 0\n0 1 0\n0 0 1\n");
    const auto r = surfvp("eval " + dir + "/g1.key " + dir + "/g1.key --homography " + identity + " --images " +
                          test::graf(1) + " " + test::graf(1));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    // Each keypoint's nearest descriptor is its own copy at distance 0.
    EXPECT_EQ(j["candidates"].get<int>(), 300);
    EXPECT_EQ(j["valid"].get<int>(), 300);
    EXPECT_EQ(j["distinguishability"].get<double>(), 1.0);
    EXPECT_EQ(j["status"], "ok");
    EXPECT_EQ(j["repeatability"].get<double>(), 1.0);
    EXPECT_EQ(j["matches"].get<int>(), j["visible_a"].get<int>());
    EXPECT_EQ(j["precision"].get<double>(), 1.0);
}

TEST(QualityCli, EvalGrafPairUnderItsHomography) {
    REQUIRE_OPENCV_DATA("graf1.png");
    REQUIRE_OPENCV_DATA("graf3.png");
    REQUIRE_OPENCV_DATA("H1to3p.xml");
    const std::string dir = fresh_dir("eval_graf");
    // One threshold for both images, the one that gives graf1 3000 keypoints (as sw/surf's test).
    const auto s1 = surfvp("surf " + test::graf(1) + " --target-count 3000 --out " + dir + "/g1.key");
    ASSERT_EQ(s1.exit_code, 0) << s1.err;
    const std::string threshold = surf_summary(s1.err).threshold;
    ASSERT_EQ(surfvp("surf " + test::graf(3) + " --threshold " + threshold + " -q --out " + dir + "/g3.key").exit_code,
              0);

    const auto r = surfvp("eval " + dir + "/g1.key " + dir + "/g3.key -H " + kOpencvData + "/H1to3p.xml --images " +
                          test::graf(1) + " " + test::graf(3));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::ordered_json::parse(r.out);  // keeps the printed key order
    const std::vector<std::string> leading = {"candidates",    "valid",           "distinguishability", "status",
                                              "repeatability", "correspondences", "precision"};
    std::vector<std::string> keys;
    for (const auto& item : j.items()) keys.push_back(item.key());
    ASSERT_GE(keys.size(), leading.size());
    EXPECT_EQ(std::vector<std::string>(keys.begin(), keys.begin() + 7), leading) << "stable key order";
    EXPECT_EQ(j["a"]["keypoints"].get<int>(), 3000);
    // Measured: precision 0.690 (263 of 381), repeatability 0.573; the bounds leave room for
    // other compilers' rounding.
    EXPECT_GE(j["precision"].get<double>(), 0.6);
    EXPECT_GT(j["repeatability"].get<double>(), 0.5);
    EXPECT_LT(j["repeatability"].get<double>(), 0.65);
    EXPECT_GT(j["correspondences"].get<int>(), j["matches"].get<int>());
    EXPECT_EQ(j["precision_candidates"], j["candidates"]);
    EXPECT_EQ(j["status"], "ok");
}

// The float reference at its defaults against the best CPU SURF on the issue's two measures:
// castle-simu (i, i + 1) at 100 keypoints per frame, no radius, no Laplacian (OpenCV's SURF:
// 0.921), and graf1 -> graf3 precision at ~2900 keypoints (OpenSURF: 0.643) without losing the
// repeatability of the paper's SURF (0.521). Measured: 0.946; 0.674 and 0.573. With --paper
// (the paper's SURF): 0.899; 0.601 and 0.521 (docs/quality.md; sw/surf's GrafMatching tests
// hold the paper's SURF below the bar).
TEST(QualityCli, TheFloatReferenceIsAtLeastAsGoodAsTheBestCpuSurf) {
    REQUIRE_CASTLE();
    REQUIRE_OPENCV_DATA("graf1.png");
    REQUIRE_OPENCV_DATA("graf3.png");
    REQUIRE_OPENCV_DATA("H1to3p.xml");
    const auto castle = surfvp("eval-seq " + kCastle + " --target-count 100 -q");
    ASSERT_EQ(castle.exit_code, 0) << castle.err;
    EXPECT_GE(json::parse(castle.out)["gaps"][0]["rows"][0]["mean"].get<double>(), 0.921);
    const std::string dir = fresh_dir("best_cpu_surf");
    const auto s1 = surfvp("surf " + test::graf(1) + " --target-count 2900 --out " + dir + "/g1.key");
    ASSERT_EQ(s1.exit_code, 0) << s1.err;
    const std::string threshold = surf_summary(s1.err).threshold;
    ASSERT_EQ(surfvp("surf " + test::graf(3) + " --threshold " + threshold + " -q --out " + dir + "/g3.key").exit_code,
              0);
    const auto r = surfvp("eval " + dir + "/g1.key " + dir + "/g3.key -H " + kOpencvData + "/H1to3p.xml --images " +
                          test::graf(1) + " " + test::graf(3));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json best = json::parse(r.out);
    EXPECT_GE(best["precision"].get<double>(), 0.643);
    EXPECT_GE(best["repeatability"].get<double>(), 0.521);
}

TEST(QualityCli, EvalWithAHomographyNeedsTheImages) {
    REQUIRE_OPENCV_DATA("graf1.png");
    const std::string dir = fresh_dir("eval_needs");
    ASSERT_EQ(surfvp("surf " + test::graf(1) + " --target-count 50 -q --out " + dir + "/g1.key").exit_code, 0);
    const std::string identity = write_file(dir, "identity.txt", "1 0 0\n0 1 0\n0 0 1\n");
    const auto r = surfvp("eval " + dir + "/g1.key " + dir + "/g1.key --homography " + identity);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--images"), std::string::npos) << r.err;
    const auto bad = surfvp("eval " + dir + "/g1.key " + write_file(dir, "bad.key", "64\n2\n1 2 3\n"));
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find(dir + "/bad.key:3:"), std::string::npos) << "file and line: " << bad.err;
}

const json* find_row(const json& gap, bool limited, bool laplacian) {
    for (const auto& row : gap["rows"])
        if (row["search_radius"].is_null() != limited && row["same_laplacian"].get<bool>() == laplacian) return &row;
    return nullptr;
}

// Keypoints computed elsewhere: the chip's own keypoint files give, through eval-seq, the
// distinguishability its run reported; a folder with a file too few is refused.
TEST(QualityCli, EvalSeqTakesTheChipsKeypointFiles) {
    REQUIRE_CASTLE();
    const std::string run = fresh_dir("chip_keypoints");
    ASSERT_EQ(surfvp("run castle_sequence --direct --quiet --set surf.frames=6 --out " + run).exit_code, 0);
    const json report = json::parse(slurp(run + "/report.json"));
    const std::string common =
        "eval-seq " + kCastle + " --poses " + kCastle + "/CameraPose --intrinsics 700,700,320,240 --frames 6";
    const auto r = surfvp(common + " --quiet --keypoints-from " + run + "/keypoints");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json row = json::parse(r.out)["gaps"][0]["rows"][0];
    const json& chip = report["workload"]["evaluation"]["distinguishability_gap1"];
    EXPECT_DOUBLE_EQ(row["mean"].get<double>(), chip["ransac"].get<double>());
    EXPECT_DOUBLE_EQ(row["ground_truth"]["mean"].get<double>(), chip["ground_truth"].get<double>());
    std::filesystem::remove(run + "/keypoints/frame_0005.surf");
    const auto short_of_one = surfvp(common + " --keypoints-from " + run + "/keypoints");
    EXPECT_EQ(short_of_one.exit_code, 2);
    EXPECT_NE(short_of_one.err.find("5 keypoint files for 6 frames"), std::string::npos) << short_of_one.err;
}

TEST(QualityCli, EvalSeqCastleRansacAgreesWithGroundTruth) {
    REQUIRE_CASTLE();
    const auto r = surfvp("eval-seq " + kCastle + " --poses " + kCastle +
                          "/CameraPose --intrinsics 700,700,320,240 --frames 6 --gap 1 --target-count 100 --table");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["frames"].get<int>(), 6);
    EXPECT_EQ(j["first_frame"], "Image_0001.pgm");
    EXPECT_EQ(j["surf"]["keypoints"]["min"].get<int>(), 100);
    EXPECT_EQ(j["surf"]["keypoints"]["max"].get<int>(), 100);
    ASSERT_EQ(j["gaps"].size(), 1u);
    const json& gap = j["gaps"][0];
    EXPECT_EQ(gap["gap"].get<int>(), 1);
    ASSERT_EQ(gap["rows"].size(), 4u);
    // The paper's row order: limited search Y Y N N, Laplacian Y N Y N.
    EXPECT_EQ(gap["rows"][0]["search_radius"].get<double>(), 200.0);
    EXPECT_TRUE(gap["rows"][0]["same_laplacian"].get<bool>());
    EXPECT_TRUE(gap["rows"][3]["search_radius"].is_null());
    EXPECT_FALSE(gap["rows"][3]["same_laplacian"].get<bool>());
    for (const auto& row : gap["rows"]) {
        for (const char* key : {"mean", "mean_of_measured", "pairs", "measured_pairs", "candidates", "valid",
                                "ground_truth", "ransac_minus_ground_truth"})
            ASSERT_TRUE(row.contains(key)) << key;
        EXPECT_EQ(row["pairs"].get<int>(), 5);
        EXPECT_EQ(row["measured_pairs"].get<int>(), 5);
        // Measured on frames 1-6: RANSAC 0.993, ground truth 0.984 on every row (the paper's
        // SURF: 0.931-0.943 and 0.904-0.916); over all 40 frames <= 0.004 apart
        // (docs/quality.md). The issue's bound: 0.05.
        const double ransac = row["mean"].get<double>(), truth = row["ground_truth"]["mean"].get<double>();
        EXPECT_NEAR(ransac, truth, 0.05);
        EXPECT_DOUBLE_EQ(row["ransac_minus_ground_truth"].get<double>(), ransac - truth);
        EXPECT_GT(truth, 0.75);
        EXPECT_LE(row["valid"].get<int>(), row["candidates"].get<int>());
    }
    ASSERT_NE(find_row(gap, false, false), nullptr);
    EXPECT_NE(r.err.find("6 frames"), std::string::npos) << r.err;
}

// A folder laid out like ViSP's (Images/, CameraPose/) whose Images/ also holds a picture
// that is no frame: it is skipped, the numbered ones are paired with their poses by number.
TEST(QualityCli, EvalSeqPairsFramesWithPosesByNumberAndSkipsOtherImages) {
    REQUIRE_CASTLE();
    const std::string dir = fresh_dir("posed");
    fs::create_directories(dir + "/Images");
    fs::create_directories(dir + "/CameraPose");
    for (const char* n : {"01", "02", "03"}) {
        fs::copy_file(kCastle + "/Images/Image_00" + n + ".pgm", dir + "/Images/Image_00" + n + ".pgm");
        fs::copy_file(kCastle + "/CameraPose/Camera_0" + n + ".txt", dir + "/CameraPose/Camera_0" + n + ".txt");
    }
    fs::copy_file(kCastle + "/Images/Image_0010.pgm", dir + "/Images/background.pgm");
    const std::string args = " --poses " + dir + "/CameraPose --intrinsics 700,700,320,240 --target-count 50 -q";
    const auto r = surfvp("eval-seq " + dir + args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["frames"].get<int>(), 3);
    EXPECT_EQ(j["skipped"], json::array({"background.pgm"}));
    EXPECT_EQ(j["last_frame"], "Image_0003.pgm");
    EXPECT_GT(j["gaps"][0]["rows"][0]["ground_truth"]["mean"].get<double>(), 0.7);

    // A numbered frame without its pose is an error naming the frame.
    fs::copy_file(kCastle + "/Images/Image_0004.pgm", dir + "/Images/Image_0004.pgm");
    const auto missing = surfvp("eval-seq " + dir + args);
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("Image_0004.pgm: no pose file"), std::string::npos) << missing.err;
}

TEST(QualityCli, EvalSeqOnAStaticCameraVideoIsNearlyPerfect) {
    REQUIRE_OPENCV_DATA("vtest.avi");
    const auto r = surfvp("eval-seq " + kOpencvData + "/vtest.avi --frames 6 --gap 1 --gap 2 -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["frames"].get<int>(), 6);
    EXPECT_EQ(j["first_frame"], "vtest.avi#0");
    ASSERT_EQ(j["gaps"].size(), 2u);
    EXPECT_EQ(j["gaps"][1]["gap"].get<int>(), 2);
    EXPECT_EQ(j["gaps"][1]["rows"][0]["pairs"].get<int>(), 4);
    // Only the walking people move; measured 0.979 here (0.979 over 20 frames).
    EXPECT_GT(j["gaps"][0]["rows"][0]["mean"].get<double>(), 0.95);
    EXPECT_FALSE(j["gaps"][0]["rows"][0].contains("ground_truth"));
}

// The pixel of `canvas` nearest (x, y), if inside.
std::optional<cv::Vec3b> pixel(const cv::Mat& canvas, double x, double y) {
    const int col = static_cast<int>(std::lround(x)), row = static_cast<int>(std::lround(y));
    if (col < 0 || row < 0 || col >= canvas.cols || row >= canvas.rows) return std::nullopt;
    return canvas.at<cv::Vec3b>(row, col);
}

// Red (BGR channel 2 strongest) for +1, blue (channel 0) for -1, within a pixel of (x, y).
bool coloured_near(const cv::Mat& canvas, double x, double y, int laplacian) {
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const auto p = pixel(canvas, x + dx, y + dy);
            if (!p) continue;
            const int strong = laplacian > 0 ? 2 : 0, weak = laplacian > 0 ? 0 : 2;
            if ((*p)[strong] > (*p)[weak] + 60 && (*p)[strong] > (*p)[1]) return true;
        }
    return false;
}

TEST(QualityCli, DrawMarksEachKeypointInItsSignsColour) {
    REQUIRE_OPENCV_DATA("graf1.png");
    const std::string dir = fresh_dir("draw");
    ASSERT_EQ(surfvp("surf " + test::graf(1) + " --target-count 40 -q --out " + dir + "/g1.key").exit_code, 0);
    const auto r = surfvp("draw " + test::graf(1) + " " + dir + "/g1.key --out " + dir + "/g1.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const cv::Mat canvas = cv::imread(dir + "/g1.png", cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(canvas.empty());
    EXPECT_EQ(canvas.size(), cv::Size(800, 640));
    ASSERT_EQ(canvas.type(), CV_8UC3);
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();

    // .meta lines: x y scale orientation response laplacian. The circle (r = 2.5 s) passes
    // through the orientation's tip and a quarter turn further.
    std::istringstream meta(slurp(dir + "/g1.key.meta"));
    std::size_t count = 0, marked = 0;
    meta >> count;
    ASSERT_EQ(count, 40u);
    for (std::size_t i = 0; i < count; ++i) {
        double x, y, s, angle, response;
        int sign;
        meta >> x >> y >> s >> angle >> response >> sign;
        const double r = 2.5 * s;
        if (coloured_near(canvas, x + r * std::cos(angle), y + r * std::sin(angle), sign) &&
            coloured_near(canvas, x + 0.5 * r * std::cos(angle), y + 0.5 * r * std::sin(angle), sign))
            ++marked;
    }
    // Overlapping circles of the other sign may cover a few.
    EXPECT_GE(marked, 36u);

    // Where there is no keypoint the image stays grey: the top-left 20x20 block of graf1.
    std::size_t grey = 0;
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) {
            const cv::Vec3b& p = canvas.at<cv::Vec3b>(y, x);
            grey += p[0] == p[1] && p[1] == p[2];
        }
    EXPECT_EQ(grey, 400u);
}

TEST(QualityCli, DrawRefusesAnUnknownImageType) {
    REQUIRE_OPENCV_DATA("graf1.png");
    const std::string dir = fresh_dir("draw_type");
    ASSERT_EQ(surfvp("surf " + test::graf(1) + " --target-count 10 -q --out " + dir + "/g1.key").exit_code, 0);
    const auto r = surfvp("draw " + test::graf(1) + " " + dir + "/g1.key --out " + dir + "/g1.nope");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--out " + dir + "/g1.nope"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/g1.nope"));
}

}  // namespace
}  // namespace surfvp
