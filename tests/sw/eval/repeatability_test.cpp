// Repeatability (IJCV 2005 §4.1 as in vlbenchmarks) and matching precision under a homography,
// on synthetic keypoints whose true correspondences are known by construction.
#include "sw/eval/repeatability.h"

#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "sw/eval/eval_test_support.h"
#include "sw/eval/homography.h"
#include "sw/eval/region.h"

namespace surfvp::eval {
namespace {

using test::Random;

const cv::Size kImage(800, 640);

// A's keypoints moved by h; the scale follows the local area change, so the circle has the
// area of the mapped region (exactly the mapped region for a similarity).
surf::Keypoints mapped(const surf::Keypoints& a, const Eigen::Matrix3d& h) {
    surf::Keypoints b = a;
    for (auto& k : b) {
        Eigen::Vector2d p(k.x, k.y);
        Eigen::Vector2d q = apply_homography(h, p);
        k.x = static_cast<float>(q.x());
        k.y = static_cast<float>(q.y());
        k.scale = static_cast<float>(k.scale * std::sqrt(std::abs(homography_jacobian(h, p).determinant())));
    }
    return b;
}

TEST(Repeatability, SetWithItselfIsOne) {
    Random random(11);
    auto a = test::random_keypoints(random, 300, kImage.width, kImage.height);
    RepeatabilityResult r = repeatability(a, a, Eigen::Matrix3d::Identity(), kImage, kImage);
    EXPECT_GT(r.visible_a, 280u);  // a few near the border are dropped
    EXPECT_LT(r.visible_a, 300u);
    EXPECT_EQ(r.visible_b, r.visible_a);
    EXPECT_EQ(r.matches.size(), r.visible_a);
    EXPECT_EQ(r.repeatability, 1.0);
    for (const auto& m : r.matches) {
        EXPECT_EQ(m.a, m.b);
        EXPECT_LT(m.overlap_error, 1e-5);
    }
}

TEST(Repeatability, KnownShiftWithItsHomographyIsRepeatable) {
    Random random(12);
    auto a = test::random_keypoints(random, 300, kImage.width, kImage.height);
    Eigen::Matrix3d h = translation_homography(13.7, -8.2);
    auto b = mapped(a, h);
    for (auto& k : b) {  // detector noise: 0.3 px position, 2 % scale
        k.x += static_cast<float>(random.uniform(-0.3, 0.3));
        k.y += static_cast<float>(random.uniform(-0.3, 0.3));
        k.scale *= static_cast<float>(random.uniform(0.98, 1.02));
    }
    RepeatabilityResult r = repeatability(a, b, h, kImage, kImage);
    EXPECT_GT(r.visible_a, 250u);
    EXPECT_GE(r.repeatability, 0.99);
    RecordProperty("repeatability", ::testing::PrintToString(r.repeatability));
    // The same keypoints judged against the identity: a 16 px offset is not a correspondence;
    // what remains are chance overlaps with other, nearby regions (0.074 here).
    RepeatabilityResult wrong = repeatability(a, b, Eigen::Matrix3d::Identity(), kImage, kImage);
    EXPECT_LT(wrong.repeatability, 0.15);
    RecordProperty("repeatability_wrong_h", ::testing::PrintToString(wrong.repeatability));
}

TEST(Repeatability, SimilarityWithItsHomographyIsOne) {
    Random random(13);
    auto a = test::random_keypoints(random, 300, kImage.width, kImage.height);
    const double angle = 0.5, zoom = 1.5;
    Eigen::Matrix3d h;
    h << zoom * std::cos(angle), -zoom * std::sin(angle), 300, zoom * std::sin(angle), zoom * std::cos(angle), -250, 0,
        0, 1;
    auto b = mapped(a, h);
    RepeatabilityResult r = repeatability(a, b, h, kImage, kImage);
    EXPECT_GT(r.visible_a, 60u);  // the part of A that lands inside B
    EXPECT_EQ(r.visible_b, r.visible_a);
    EXPECT_EQ(r.repeatability, 1.0);
    for (const auto& m : r.matches) EXPECT_EQ(m.a, m.b);
}

TEST(Repeatability, HalfTheRegionsMovedFarGivesOneHalf) {
    // A lives in the left half of a 1000x600 image; half of B moved 500 px right is more than
    // 100 px (a normalised region's radius at most) from every A region.
    const cv::Size image(1000, 600);
    Random random(14);
    surf::Keypoints a;
    for (int i = 0; i < 200; ++i) {
        auto k = test::random_keypoint(random, 1, 1, 1.2, 4.0);
        k.x = static_cast<float>(random.uniform(50, 450));
        k.y = static_cast<float>(random.uniform(50, 550));
        a.push_back(k);
    }
    surf::Keypoints b = a;
    for (std::size_t i = 0; i < b.size(); i += 2) b[i].x += 500;
    RepeatabilityResult r = repeatability(a, b, Eigen::Matrix3d::Identity(), image, image);
    EXPECT_EQ(r.visible_a, 200u);
    EXPECT_EQ(r.visible_b, 200u);
    EXPECT_EQ(r.matches.size(), 100u);
    EXPECT_EQ(r.repeatability, 0.5);
    for (const auto& m : r.matches) EXPECT_EQ(m.a % 2, 1u);
}

TEST(Repeatability, RandomHalfMovedIsAboutOneHalf) {
    // Every visible region left in place matches its twin; the moved half adds chance overlaps
    // and changes B's visible count a little.
    Random random(15);
    auto a = test::random_keypoints(random, 200, kImage.width, kImage.height);
    auto b = a;
    for (std::size_t i = 0; i < b.size(); i += 2) {  // anywhere else in the image
        b[i].x = static_cast<float>(random.uniform(0, kImage.width));
        b[i].y = static_cast<float>(random.uniform(0, kImage.height));
    }
    RepeatabilityResult r = repeatability(a, b, Eigen::Matrix3d::Identity(), kImage, kImage);
    EXPECT_NEAR(r.repeatability, 0.5, 0.03);
    RecordProperty("repeatability", ::testing::PrintToString(r.repeatability));
    std::size_t in_place_visible = 0, in_place_matched = 0;
    for (std::size_t i = 1; i < a.size(); i += 2) {
        in_place_visible += region_visible(keypoint_region(a[i]), kImage);
    }
    for (const auto& m : r.matches) in_place_matched += (m.a == m.b && m.a % 2 == 1);
    EXPECT_EQ(in_place_matched, in_place_visible);
}

TEST(Repeatability, OnlyRegionsVisibleInBothImagesCount) {
    surf::Keypoint inside, border, outside_b;
    inside.x = 100, inside.y = 100, inside.scale = 4;           // r = 10
    border.x = 9, border.y = 100, border.scale = 4;             // reaches x = -1
    outside_b.x = 700, outside_b.y = 100, outside_b.scale = 4;  // beyond B's width of 600
    surf::Keypoints a = {inside, border, outside_b};
    RepeatabilityResult r = repeatability(a, a, Eigen::Matrix3d::Identity(), kImage, cv::Size(600, 640));
    EXPECT_EQ(r.visible_a, 1u);
    EXPECT_EQ(r.visible_b, 1u);
    ASSERT_EQ(r.matches.size(), 1u);
    EXPECT_EQ(r.matches[0].a, 0u);
    EXPECT_TRUE(region_visible(Ellipse::circle({10.5, 50}, 10), kImage));
    EXPECT_FALSE(region_visible(Ellipse::circle({10.0, 50}, 10), kImage));  // touches x = 0
}

TEST(Repeatability, OverlapErrorIsMeasuredOnNormalisedRegions) {
    // Two radius-3 circles 1 px apart: rescaled to radius 30 with the centres kept 1 px apart,
    // the error is that of radius-30 circles 1 px apart (0.042), not of radius-3 ones (0.349).
    double small = overlap_error(Ellipse::circle({0, 0}, 3), Ellipse::circle({1, 0}, 3));
    double large = overlap_error(Ellipse::circle({0, 0}, 30), Ellipse::circle({1, 0}, 30));
    EXPECT_NEAR(small, large, 1e-6);
    EXPECT_NEAR(large, 0.04155, 1e-4);
    double raw = 1 - ellipse_overlap(Ellipse::circle({0, 0}, 3), Ellipse::circle({1, 0}, 3));
    EXPECT_NEAR(raw, 0.3488, 1e-3);
}

TEST(Repeatability, GreedyMatchingIsOneToOne) {
    // Two A regions and one B region between them: one match, to the closer A.
    surf::Keypoint a1, a2, b1;
    a1.x = 100, a1.y = 100, a1.scale = 10;
    a2.x = 104, a2.y = 100, a2.scale = 10;
    b1.x = 101, b1.y = 100, b1.scale = 10;
    RepeatabilityResult r = repeatability({a1, a2}, {b1}, Eigen::Matrix3d::Identity(), kImage, kImage);
    EXPECT_EQ(r.correspondences, 2u);
    ASSERT_EQ(r.matches.size(), 1u);
    EXPECT_EQ(r.matches[0].a, 0u);
    EXPECT_EQ(r.repeatability, 1.0);  // 1 / min(2, 1)
}

TEST(Repeatability, RealGraffitiHomography) {
    const std::string data = OPENCV_DATA_DIR;
    ASSERT_TRUE(test::package_file(data + "/H1to3p.xml", "opencv-doc"));
    ASSERT_TRUE(test::package_file(data + "/graf1.png", "opencv-doc"));
    ASSERT_TRUE(test::package_file(data + "/graf3.png", "opencv-doc"));
    Eigen::Matrix3d h = read_homography_file(data + "/H1to3p.xml");
    cv::Size size_a = cv::imread(data + "/graf1.png", cv::IMREAD_GRAYSCALE).size();
    cv::Size size_b = cv::imread(data + "/graf3.png", cv::IMREAD_GRAYSCALE).size();
    ASSERT_EQ(size_a, cv::Size(800, 640));
    Random random(16);
    auto a = test::random_keypoints(random, 400, size_a.width, size_a.height);
    auto b = mapped(a, h);  // circles of the right area where H makes ellipses
    RepeatabilityResult r = repeatability(a, b, h, size_a, size_b);
    EXPECT_GT(r.visible_a, 300u);
    // A circle and the ellipse H makes of it reach out differently: the two visible sets differ
    // near the borders by a region or two.
    EXPECT_LE(std::max(r.visible_a, r.visible_b) - std::min(r.visible_a, r.visible_b), 3u);
    // The anisotropy of H1to3p's Jacobian costs up to ~0.3 of overlap: nearly all still match.
    EXPECT_GE(r.repeatability, 0.99);
    double worst = 0;
    for (const auto& m : r.matches) {
        EXPECT_EQ(m.a, m.b);
        worst = std::max(worst, m.overlap_error);
    }
    EXPECT_GT(worst, 0.1);  // the ellipse-vs-circle shape difference is really measured
    RecordProperty("repeatability", ::testing::PrintToString(r.repeatability));
    RecordProperty("visible", std::to_string(r.visible_a) + " / " + std::to_string(r.visible_b));
    RecordProperty("worst_overlap_error", ::testing::PrintToString(worst));
    RepeatabilityResult identity = repeatability(a, b, Eigen::Matrix3d::Identity(), size_a, size_b);
    EXPECT_LT(identity.repeatability, 0.15);  // chance overlaps only
    RecordProperty("repeatability_identity", ::testing::PrintToString(identity.repeatability));
}

TEST(MatchingPrecision, CorrectWhenTheHomographyMapsWithinThreePixels) {
    Random random(17);
    auto a = test::random_keypoints(random, 100, kImage.width, kImage.height);
    Eigen::Matrix3d h = translation_homography(40, 25);
    auto b = mapped(a, h);
    for (std::size_t i = 0; i < b.size(); i += 4) b[i].y += 2.5f;  // off, but within 3 px
    for (std::size_t i = 1; i < b.size(); i += 4) b[i].y += 3.5f;  // off by more than 3 px
    PrecisionResult p = matching_precision(a, b, h);
    EXPECT_EQ(p.candidates, 100u);  // identical descriptors pass the ratio test
    EXPECT_EQ(p.correct, 75u);
    EXPECT_EQ(p.precision, 0.75);
    EXPECT_NEAR(p.errors[0], 2.5, 1e-4);
    EXPECT_NEAR(p.errors[1], 3.5, 1e-4);
    EXPECT_NEAR(p.errors[2], 0.0, 1e-4);
    PrecisionResult wrong = matching_precision(a, b, Eigen::Matrix3d::Identity());
    EXPECT_EQ(wrong.correct, 0u);
    EXPECT_EQ(matching_precision({}, b, h).precision, 0.0);
}

}  // namespace
}  // namespace surfvp::eval
