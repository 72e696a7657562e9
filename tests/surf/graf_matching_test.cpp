// Matching quality on the Graffiti pair (Mikolajczyk's viewpoint sequence, shipped by opencv-doc):
// graf1 -> graf3 is a 40-degree viewpoint change with a known homography.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include "sw/surf/surf.h"
#include "tests/surf/test_data.h"

namespace surfvp::surf {
namespace {

// Rows are descriptors.
Eigen::MatrixXf descriptor_matrix(const Keypoints& kps) {
    Eigen::MatrixXf m(static_cast<Eigen::Index>(kps.size()), 64);
    for (size_t i = 0; i < kps.size(); ++i)
        for (int k = 0; k < 64; ++k) m(static_cast<Eigen::Index>(i), k) = kps[i].descriptor[static_cast<size_t>(k)];
    return m;
}

struct MatchScore {
    int candidates = 0;
    int correct = 0;
    double precision() const { return candidates ? static_cast<double>(correct) / candidates : 0.0; }
};

// Brute-force Euclidean nearest / second nearest, ratio test < 0.75 (paper §IV-A); a candidate is
// correct when H maps the first point within 3 px of its match.
MatchScore ratio_test_precision(const Keypoints& a, const Keypoints& b, const cv::Matx33d& h) {
    const Eigen::MatrixXf da = descriptor_matrix(a), db = descriptor_matrix(b);
    const Eigen::VectorXf na = da.rowwise().squaredNorm(), nb = db.rowwise().squaredNorm();
    const Eigen::MatrixXf dot = da * db.transpose();
    MatchScore score;
    for (Eigen::Index i = 0; i < da.rows(); ++i) {
        float best = INFINITY, second = INFINITY;
        Eigen::Index best_j = -1;
        for (Eigen::Index j = 0; j < db.rows(); ++j) {
            const float d2 = std::max(0.0f, na(i) + nb(j) - 2 * dot(i, j));
            if (d2 < best) {
                second = best;
                best = d2;
                best_j = j;
            } else if (d2 < second) {
                second = d2;
            }
        }
        if (best_j < 0 || !(std::sqrt(best) < 0.75f * std::sqrt(second))) continue;
        ++score.candidates;
        const Keypoint& p = a[static_cast<size_t>(i)];
        const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1.0);
        const Keypoint& m = b[static_cast<size_t>(best_j)];
        if (std::hypot(q[0] / q[2] - m.x, q[1] / q[2] - m.y) < 3.0) ++score.correct;
    }
    return score;
}

TEST(GrafMatching, RatioTestPrecisionUnderHomographyIsAtLeastOpenCvs) {
    const cv::Mat graf1 = test::opencv_gray("graf1.png");
    const cv::Mat graf3 = test::opencv_gray("graf3.png");
    const std::string h_path = test::opencv_data("H1to3p.xml");
    ASSERT_FALSE(graf1.empty() || graf3.empty() || h_path.empty());
    cv::Mat h_mat;
    cv::FileStorage(h_path, cv::FileStorage::READ)["H13"] >> h_mat;
    ASSERT_EQ(h_mat.size(), cv::Size(3, 3)) << h_path << " has no 3x3 matrix H13";
    const cv::Matx33d h(h_mat);

    Params params;
    params.threshold = threshold_for_count(graf1, 3000, params);
    const Keypoints k1 = detect_and_describe(graf1, params);
    const Keypoints k3 = detect_and_describe(graf3, params);
    const MatchScore score = ratio_test_precision(k1, k3, h);

    std::cout << "graf1->graf3: threshold " << params.threshold << ", keypoints " << k1.size() << " / " << k3.size()
              << ", candidates " << score.candidates << ", correct " << score.correct << ", precision "
              << score.precision() << "\n";
    RecordProperty("threshold", std::to_string(params.threshold));
    RecordProperty("keypoints_graf1", static_cast<int>(k1.size()));
    RecordProperty("precision", std::to_string(score.precision()));

    EXPECT_GE(k1.size(), 2500u);
    EXPECT_LE(k1.size(), 3500u);
    EXPECT_GT(score.candidates, 300);  // a precision over a handful of matches means nothing
    // OpenCV's own SURF scores ~0.56 here (threshold 400, ~2900 keypoints). Measured here: 0.591
    // at 3000; over 2500..3500 keypoints 0.544 (2500 only), else 0.576..0.601.
    EXPECT_GE(score.precision(), 0.55);
}

// The same pair with rounded Haar wavelets (HaarMode::rounded: whole-pixel positions and
// sizes, integer box sums, as OpenSURF and embedded SURF code compute them).
TEST(GrafMatching, RoundedHaarWaveletsKeepMostOfThePrecision) {
    const cv::Mat graf1 = test::opencv_gray("graf1.png");
    const cv::Mat graf3 = test::opencv_gray("graf3.png");
    const std::string h_path = test::opencv_data("H1to3p.xml");
    ASSERT_FALSE(graf1.empty() || graf3.empty() || h_path.empty());
    cv::Mat h_mat;
    cv::FileStorage(h_path, cv::FileStorage::READ)["H13"] >> h_mat;
    ASSERT_EQ(h_mat.size(), cv::Size(3, 3)) << h_path << " has no 3x3 matrix H13";
    const cv::Matx33d h(h_mat);

    Params params;
    params.haar = HaarMode::rounded;
    params.threshold = threshold_for_count(graf1, 3000, params);
    const Keypoints k1 = detect_and_describe(graf1, params);
    const Keypoints k3 = detect_and_describe(graf3, params);
    const MatchScore score = ratio_test_precision(k1, k3, h);

    std::cout << "graf1->graf3 (rounded Haar): threshold " << params.threshold << ", keypoints " << k1.size() << " / "
              << k3.size() << ", candidates " << score.candidates << ", correct " << score.correct << ", precision "
              << score.precision() << "\n";
    RecordProperty("precision", std::to_string(score.precision()));

    EXPECT_GE(k1.size(), 2500u);
    EXPECT_LE(k1.size(), 3500u);
    EXPECT_GT(score.candidates, 300);
    // Measured: 0.540 (170 of 315 candidates) at 3000 keypoints, against 0.591 (208 of 352)
    // exact (the test above); over 2500..3500 keypoints in steps of 100, 0.539..0.558 (exact
    // 0.544..0.601).
    EXPECT_GE(score.precision(), 0.50);
}

}  // namespace
}  // namespace surfvp::surf
