// Synthetic Gaussian blobs of known size and position.
//
// Expected scale. With Gaussian derivatives, the scale-normalised determinant of the Hessian of a
// Gaussian blob of standard deviation sigma peaks at sigma (Lindeberg 1998). SURF's box filters
// normalised by L^2 do not: at the blob centre (Dxy = 0) the response is (Box(Dyy) / L^2)^2,
// which peaks at a filter size L* with s* = 1.2 L* / 9 ~= 0.72 sigma for sigma = 2.4 and
// 0.67 sigma for large blobs. expected_scale() computes s* in closed form (the blob's integral
// over each box is a product of normal CDFs) and the detector must find s within 12 % of it
// (the scale axis is sampled at 2 filter sizes per octave and interpolated by a quadratic).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include <opencv2/core.hpp>

#include "sw/surf/surf.h"

namespace surfvp::surf {
namespace {

cv::Mat gaussian_blob(int width, int height, double cx, double cy, double sigma, int background, int peak) {
    cv::Mat img(height, width, CV_8UC1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            img.at<uint8_t>(y, x) =
                cv::saturate_cast<uint8_t>(background + (peak - background) * std::exp(-r2 / (2 * sigma * sigma)));
        }
    return img;
}

double normal_cdf(double z) { return 0.5 * (1 + std::erf(z / std::sqrt(2.0))); }

// Integral of a unit Gaussian blob of std sigma over [x0, x1] x [y0, y1].
double blob_mass(double x0, double x1, double y0, double y1, double sigma) {
    return (normal_cdf(x1 / sigma) - normal_cdf(x0 / sigma)) * (normal_cdf(y1 / sigma) - normal_cdf(y0 / sigma));
}

// s* of the box-filter determinant at the centre of a Gaussian blob, with the filter of size L
// in continuous form: lobe l = L / 3, Dyy = whole (2l - 1) x 3l box - 3 x middle (2l - 1) x l box,
// pixel edges at +-0.5.
double expected_scale(double sigma) {
    double best_det = 0, best_size = 0;
    for (double size = 6; size < 40 * sigma; size += 0.05) {
        const double l = size / 3;
        const double dyy = blob_mass(-(l - 0.5), l - 0.5, -1.5 * l, 1.5 * l, sigma) -
                           3 * blob_mass(-(l - 0.5), l - 0.5, -l / 2, l / 2, sigma);
        const double det = (dyy / (size * size)) * (dyy / (size * size));
        if (det > best_det) {
            best_det = det;
            best_size = size;
        }
    }
    return 1.2 * best_size / 9;
}

// The strongest keypoint, which must exist.
Keypoint strongest(const Keypoints& kps) {
    Keypoint best;
    for (const Keypoint& kp : kps)
        if (kp.response > best.response) best = kp;
    return best;
}

struct BlobCase {
    double sigma;
    double cx, cy;
};

void PrintTo(const BlobCase& c, std::ostream* os) {
    *os << "sigma " << c.sigma << " at (" << c.cx << ", " << c.cy << ")";
}

class GaussianBlob : public ::testing::TestWithParam<BlobCase> {};

TEST_P(GaussianBlob, KeypointAtCentreWithTheBoxFilterScale) {
    const BlobCase c = GetParam();
    const int side = static_cast<int>(std::ceil(c.sigma * 24)) + 40;
    Params params;
    params.threshold = 10;
    for (const bool bright : {true, false}) {
        const cv::Mat img =
            gaussian_blob(side, side, c.cx * side, c.cy * side, c.sigma, bright ? 30 : 220, bright ? 220 : 30);
        const Keypoints kps = detect_and_describe(img, params);
        ASSERT_FALSE(kps.empty()) << "sigma " << c.sigma;
        const Keypoint kp = strongest(kps);
        const double dist = std::hypot(kp.x - c.cx * side, kp.y - c.cy * side);
        const double expected = expected_scale(c.sigma);
        std::cout << "blob sigma " << c.sigma << (bright ? " bright" : " dark") << ": keypoint at distance " << dist
                  << " px, scale " << kp.scale << " = " << kp.scale / c.sigma << " sigma (expected "
                  << expected / c.sigma << " sigma, error " << 100 * (kp.scale / expected - 1) << " %), " << kps.size()
                  << " keypoint(s)\n";
        EXPECT_LT(dist, 0.5) << "sigma " << c.sigma;
        EXPECT_NEAR(kp.scale / expected, 1.0, 0.12) << "sigma " << c.sigma;
        // The trace is negative on a bright blob, positive on a dark one (paper §II).
        EXPECT_EQ(kp.laplacian, bright ? -1 : 1);
        float norm2 = 0;
        for (float v : kp.descriptor) norm2 += v * v;
        EXPECT_NEAR(norm2, 1.0f, 1e-4f);
    }
}

INSTANTIATE_TEST_SUITE_P(Scales, GaussianBlob,
                         ::testing::Values(BlobCase{2.4, 0.5, 0.5}, BlobCase{3.0, 0.47, 0.53}, BlobCase{5.0, 0.5, 0.5},
                                           BlobCase{6.3, 0.52, 0.49}, BlobCase{10.0, 0.5, 0.5},
                                           BlobCase{16.0, 0.5, 0.5}),
                         [](const ::testing::TestParamInfo<BlobCase>& info) {
                             return "sigma_" + std::to_string(static_cast<int>(info.param.sigma * 10)) + "_tenths";
                         });

}  // namespace
}  // namespace surfvp::surf
