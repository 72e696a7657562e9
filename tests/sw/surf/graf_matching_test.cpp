// Matching quality on the Graffiti pair (Mikolajczyk's viewpoint sequence, shipped by opencv-doc):
// graf1 -> graf3 is a 40-degree viewpoint change with a known homography.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include "sw/surf/surf.h"
#include "tests/sw/surf/test_data.h"

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

// graf1 at 3000 keypoints, graf3 at the same threshold, under `params`: the ratio test's
// precision under H1to3p.
MatchScore graf_precision(Params params, const char* what) {
    const cv::Mat graf1 = test::opencv_gray("graf1.png");
    const cv::Mat graf3 = test::opencv_gray("graf3.png");
    const std::string h_path = test::opencv_data("H1to3p.xml");
    EXPECT_FALSE(graf1.empty() || graf3.empty() || h_path.empty());
    if (graf1.empty() || graf3.empty() || h_path.empty()) return {};
    cv::Mat h_mat;
    cv::FileStorage(h_path, cv::FileStorage::READ)["H13"] >> h_mat;
    EXPECT_EQ(h_mat.size(), cv::Size(3, 3)) << h_path << " has no 3x3 matrix H13";
    if (h_mat.size() != cv::Size(3, 3)) return {};
    params.threshold = threshold_for_count(graf1, 3000, params);
    const Keypoints k1 = detect_and_describe(graf1, params);
    const Keypoints k3 = detect_and_describe(graf3, params);
    const MatchScore score = ratio_test_precision(k1, k3, cv::Matx33d(h_mat));
    std::cout << "graf1->graf3 (" << what << "): threshold " << params.threshold << ", keypoints " << k1.size() << " / "
              << k3.size() << ", candidates " << score.candidates << ", correct " << score.correct << ", precision "
              << score.precision() << "\n";
    EXPECT_EQ(k1.size(), 3000u);
    EXPECT_GT(score.candidates, 300);  // a precision over a handful of matches means nothing
    return score;
}

// The float reference at its defaults is at least as precise as the best CPU SURF: OpenSURF
// scores 0.643 here at ~2900 keypoints, OpenCV's SURF ~0.56 (threshold 400, ~2900).
// Measured: 0.690 (263 of 381) at 3000; over 2500..3500 keypoints 0.63..0.69 (docs/quality.md).
TEST(GrafMatching, RatioTestPrecisionUnderHomographyIsAtLeastOpenSurfs) {
    const MatchScore score = graf_precision(Params{}, "defaults");
    RecordProperty("precision", std::to_string(score.precision()));
    EXPECT_GE(score.precision(), 0.643);
}

// The paper's SURF (4 intervals, offsets to 0.5, Bay's descriptor) is measurably less precise:
// measured 0.591 (208 of 352); over 2500..3500 keypoints 0.544 (2500 only), else 0.576..0.601.
TEST(GrafMatching, ThePapersSurfIsLessPrecise) {
    const MatchScore paper = graf_precision(paper_surf(), "the paper's SURF");
    EXPECT_GE(paper.precision(), 0.55);
    EXPECT_LT(paper.precision(), 0.62);
}

// Rounded Haar wavelets (HaarMode::rounded: whole-pixel positions and sizes, integer box sums,
// as OpenSURF and embedded SURF code compute them) keep most of it. Measured: the paper's SURF
// 0.540 (170 of 315) at 3000 keypoints, over 2500..3500 0.539..0.558; at the defaults 0.689.
TEST(GrafMatching, RoundedHaarWaveletsKeepMostOfThePrecision) {
    Params paper = paper_surf();
    paper.haar = HaarMode::rounded;
    EXPECT_GE(graf_precision(paper, "the paper's SURF, rounded Haar").precision(), 0.50);
    Params defaults;
    defaults.haar = HaarMode::rounded;
    EXPECT_GE(graf_precision(defaults, "defaults, rounded Haar").precision(), 0.62);
}

}  // namespace
}  // namespace surfvp::surf
