// The whole pipeline: parameters, thresholds, threads, workspaces.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "sw/surf/surf.h"
#include "tests/sw/surf/test_data.h"

namespace surfvp::surf {
namespace {

void expect_same_keypoints(const Keypoints& a, const Keypoints& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].x, b[i].x);
        EXPECT_EQ(a[i].y, b[i].y);
        EXPECT_EQ(a[i].scale, b[i].scale);
        EXPECT_EQ(a[i].orientation, b[i].orientation);
        EXPECT_EQ(a[i].response, b[i].response);
        EXPECT_EQ(a[i].laplacian, b[i].laplacian);
        EXPECT_EQ(a[i].descriptor, b[i].descriptor);
    }
}

TEST(Params, OutOfRangeValuesAreRejected) {
    const cv::Mat img(64, 64, CV_8UC1, cv::Scalar(0));
    auto with = [](auto change) {
        Params p;
        change(p);
        return p;
    };
    EXPECT_THROW(detect(img, with([](Params& p) { p.octaves = 0; })), std::invalid_argument);
    EXPECT_THROW(detect(img, with([](Params& p) { p.octaves = 5; })), std::invalid_argument);
    EXPECT_THROW(detect(img, with([](Params& p) { p.intervals = 2; })), std::invalid_argument);
    EXPECT_THROW(detect(img, with([](Params& p) { p.init_step = 3; })), std::invalid_argument);
    EXPECT_THROW(detect(img, with([](Params& p) { p.threads = -1; })), std::invalid_argument);
    EXPECT_THROW(detect(img, with([](Params& p) { p.max_offset = 0; })), std::invalid_argument);
    EXPECT_THROW(detect(img, with([](Params& p) { p.max_offset = 2.5f; })), std::invalid_argument);
    EXPECT_THROW(detect(img, with([](Params& p) { p.descriptor = DescriptorKind(7); })), std::invalid_argument);
    EXPECT_NO_THROW(detect(img, with([](Params& p) { p.octaves = 1; })));
}

TEST(ThresholdForCount, GivesTheTargetCountExactly) {
    // Maxima and interpolation do not depend on the threshold, so the count at the returned
    // threshold is exact unless two responses tie at the cut (not the case on graf1).
    const cv::Mat img = test::opencv_gray("graf1.png");
    ASSERT_FALSE(img.empty());
    for (const int init_step : {1, 2}) {
        // graf1 has 2932 maxima with a positive determinant at init_step 2, 6104 at 1.
        for (const int target : {1, 100, 1000, 2500}) {
            Params params;
            params.init_step = init_step;
            params.threshold = threshold_for_count(img, target, params);
            const size_t count = detect(img, params).size();
            std::cout << "init_step " << init_step << ", target " << target << ": threshold " << params.threshold
                      << ", " << count << " keypoints\n";
            EXPECT_GT(params.threshold, 0.0f);
            EXPECT_EQ(count, static_cast<size_t>(target));
        }
    }
}

TEST(ThresholdForCount, ReturnsZeroWhenTheImageHasFewerMaxima) {
    const cv::Mat flat(100, 100, CV_8UC1, cv::Scalar(90));
    EXPECT_EQ(threshold_for_count(flat, 100, Params{}), 0.0f);
    const cv::Mat img = test::opencv_gray("graf1.png");
    ASSERT_FALSE(img.empty());
    Params params = paper_surf();
    params.init_step = 2;
    params.threshold = threshold_for_count(img, 3000, params);
    EXPECT_EQ(params.threshold, 0.0f);  // fewer than 3000 maxima (2932): take them all
    const size_t all = detect(img, params).size();
    EXPECT_GT(all, 2000u);
    EXPECT_LT(all, 3000u);
    EXPECT_TRUE(detect(flat, Params{}).empty());
}

TEST(Pipeline, ThreadCountDoesNotChangeTheResult) {
    const cv::Mat img = test::opencv_gray("graf1.png");
    ASSERT_FALSE(img.empty());
    Params params;
    params.threshold = 60;
    params.threads = 1;
    const Keypoints one = detect_and_describe(img, params);
    params.threads = 2;
    const Keypoints two = detect_and_describe(img, params);
    params.threads = 5;
    const Keypoints five = detect_and_describe(img, params);
    EXPECT_GT(one.size(), 1000u);
    expect_same_keypoints(one, two);
    expect_same_keypoints(one, five);
}

TEST(Pipeline, WorkspaceReuseAcrossSizesGivesFreshResults) {
    const cv::Mat img = test::opencv_gray("graf1.png");
    ASSERT_FALSE(img.empty());
    const cv::Mat crop = img(cv::Rect(0, 0, 640, 800 - 160)).clone();  // 640 x 640
    const cv::Mat transposed = img.t();                                // 640 x 800
    Params params;
    params.threshold = 100;
    Workspace workspace;
    for (const cv::Mat* m : {&img, &crop, &transposed, &img}) {
        const Keypoints reused = detect_and_describe(*m, params, workspace);
        EXPECT_FALSE(reused.empty());
        expect_same_keypoints(reused, detect_and_describe(*m, params));
    }
}

TEST(Pipeline, StepsComposeAndUprightGivesZeroOrientation) {
    const cv::Mat img = test::opencv_gray("graf1.png");
    ASSERT_FALSE(img.empty());
    Params params;
    params.threshold = 200;
    Keypoints kps = detect(img, params);
    ASSERT_FALSE(kps.empty());
    for (const Keypoint& kp : kps) {
        EXPECT_EQ(kp.orientation, 0.0f);
        EXPECT_EQ(kp.descriptor, (std::array<float, 64>{}));
        EXPECT_TRUE(kp.laplacian == 1 || kp.laplacian == -1);
        EXPECT_GT(kp.response, params.threshold);
        // Interpolated scales lie max_offset (1) filter spacings around the middle intervals:
        // L = 15 - 6 (octave 0) .. 195 + 48 (octave 3).
        EXPECT_GE(kp.scale, 1.2f * 9 / 9);
        EXPECT_LE(kp.scale, 1.2f * 243 / 9);
    }
    const IntegralImage ii(img);
    describe(ii.view(), kps, params);
    expect_same_keypoints(kps, detect_and_describe(img, params));

    params.upright = true;
    const Keypoints upright = detect_and_describe(img, params);
    ASSERT_EQ(upright.size(), kps.size());
    int turned = 0;
    for (size_t i = 0; i < upright.size(); ++i) {
        EXPECT_EQ(upright[i].orientation, 0.0f);
        turned += kps[i].orientation != 0.0f;
    }
    EXPECT_GT(turned, static_cast<int>(kps.size()) / 2);
}

}  // namespace
}  // namespace surfvp::surf
