// Orientation and descriptor: ramps, and covariance under 90-degree rotations of a real image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <opencv2/core.hpp>

#include "sw/surf/descriptor.h"
#include "sw/surf/haar.h"
#include "sw/surf/orientation.h"
#include "sw/surf/surf.h"
#include "tests/sw/surf/test_data.h"

namespace surfvp::surf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Smallest absolute difference of two angles, radians.
double angle_difference(double a, double b) {
    const double d = std::fmod(std::fabs(a - b), 2 * kPi);
    return std::min(d, 2 * kPi - d);
}

// Intensity grows along direction phi (image axes, x right, y down) by 2 grey levels a pixel.
cv::Mat ramp(double phi) {
    cv::Mat img(201, 201, CV_8UC1);
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x)
            img.at<uint8_t>(y, x) =
                cv::saturate_cast<uint8_t>(128 + 2 * ((x - 100) * std::cos(phi) + (y - 100) * std::sin(phi)));
    return img;
}

TEST(Haar, ResponseOfARampOnWholePixelsIsSlopeTimesWaveletMoment) {
    // I = 128 + 2x; a wavelet of even size 2h on a pixel edge covers whole pixels, so
    // dx = 2 * h^2 * 2h exactly (midpoint rule is exact on a linear function).
    const IntegralImage ii(ramp(0));
    for (const int h : {1, 2, 4, 7}) {
        const HaarResponse r = haar_response(ii.view(), 100.5f, 99.5f, 2.0f * h);
        EXPECT_FLOAT_EQ(r.dx, 4.0f * h * h * h) << h;
        EXPECT_FLOAT_EQ(r.dy, 0.0f) << h;
    }
}

// Integral of the pixel-constant image over [x0, x1] x [y0, y1] (pixel-centre coordinates),
// pixel by pixel with its overlap area; pixels outside the image are 0.
double brute_force_area(const cv::Mat& img, double x0, double x1, double y0, double y1) {
    double sum = 0;
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x) {
            const double wx = std::max(0.0, std::min(x1, x + 0.5) - std::max(x0, x - 0.5));
            const double wy = std::max(0.0, std::min(y1, y + 0.5) - std::max(y0, y - 0.5));
            sum += wx * wy * img.at<uint8_t>(y, x);
        }
    return sum;
}

TEST(Haar, RealPositionsAndSizesIntegrateThePixelSquaresExactly) {
    cv::Mat img(40, 50, CV_8UC1);
    cv::RNG rng(12);
    rng.fill(img, cv::RNG::UNIFORM, 0, 256);
    const IntegralImage ii(img);
    for (int n = 0; n < 300; ++n) {
        // Centres from outside the image to beyond it, sizes 2..20 px.
        const float x = static_cast<float>(rng.uniform(-8.0, 58.0)), y = static_cast<float>(rng.uniform(-8.0, 48.0));
        const float size = static_cast<float>(rng.uniform(2.0, 20.0)), h = size / 2;
        const double right = brute_force_area(img, x, x + h, y - h, y + h);
        const double left = brute_force_area(img, x - h, x, y - h, y + h);
        const double bottom = brute_force_area(img, x - h, x + h, y, y + h);
        const double top = brute_force_area(img, x - h, x + h, y - h, y);
        const HaarResponse r = haar_response(ii.view(), x, y, size);
        // float position and weights: ~1e-6 relative on sums up to 255 * 400
        ASSERT_NEAR(r.dx, right - left, 0.05) << x << "," << y << " size " << size;
        ASSERT_NEAR(r.dy, bottom - top, 0.05) << x << "," << y << " size " << size;
    }
}

TEST(Haar, AreaIntegralAtPixelCornersIsTheIntegralImage) {
    const IntegralImage ii(ramp(1.0));
    const IntegralView v = ii.view();
    EXPECT_DOUBLE_EQ(area_integral(v, 10.5, 20.5), v.at(10, 20));
    EXPECT_DOUBLE_EQ(area_integral(v, -0.5, 20.5), 0.0);
    EXPECT_DOUBLE_EQ(area_integral(v, 400.0, 500.0), v.at(200, 200));  // clamped
    // Half a pixel further in x adds half of pixel column 11, rows 0..20.
    EXPECT_NEAR(area_integral(v, 11.0, 20.5) - v.at(10, 20), 0.5 * (v.at(11, 20) - v.at(10, 20)), 1e-3);
}

// HaarMode::rounded: the wavelet of side 2h centred on the pixel corner nearest to (x, y),
// i.e. (floor(x) + 0.5, floor(y) + 0.5), summed over whole pixels: equal to the pixel-by-pixel
// box sums (zero outside the image) and to the exact wavelet placed on that corner.
TEST(Haar, RoundedIsTheWholePixelWaveletOnTheNearestCorner) {
    cv::Mat img(40, 50, CV_8UC1);
    cv::RNG rng(34);
    rng.fill(img, cv::RNG::UNIFORM, 0, 256);
    const IntegralImage ii(img);
    for (int n = 0; n < 400; ++n) {
        const float x = static_cast<float>(rng.uniform(-8.0, 58.0)), y = static_cast<float>(rng.uniform(-8.0, 48.0));
        const int h = rng.uniform(1, 11);
        const double cx = std::floor(x) + 0.5, cy = std::floor(y) + 0.5;  // the nearest corner
        const double right = brute_force_area(img, cx, cx + h, cy - h, cy + h);
        const double left = brute_force_area(img, cx - h, cx, cy - h, cy + h);
        const double bottom = brute_force_area(img, cx - h, cx + h, cy, cy + h);
        const double top = brute_force_area(img, cx - h, cx + h, cy - h, cy);
        const HaarResponse r = haar_response_rounded(ii.view(), x, y, h);
        ASSERT_EQ(r.dx, static_cast<float>(right - left)) << x << "," << y << " half " << h;  // integers
        ASSERT_EQ(r.dy, static_cast<float>(bottom - top)) << x << "," << y << " half " << h;
        const HaarResponse e = haar_response(ii.view(), static_cast<float>(cx), static_cast<float>(cy), 2.0f * h);
        ASSERT_EQ(r.dx, e.dx);
        ASSERT_EQ(r.dy, e.dy);
    }
    // The corner rule: anything in [10, 11) x [20, 21) gives the wavelet at (10.5, 20.5).
    const HaarResponse a = haar_response_rounded(ii.view(), 10.0f, 20.0f, 3);
    for (const float dx : {0.2f, 0.5f, 0.99f}) {
        const HaarResponse b = haar_response_rounded(ii.view(), 10.0f + dx, 20.0f + 1 - dx, 3);
        EXPECT_EQ(a.dx, b.dx);
        EXPECT_EQ(a.dy, b.dy);
    }
}

TEST(Orientation, PointsAlongTheGradientOfARamp) {
    for (int k = 0; k < 24; ++k) {
        const double phi = k * 2 * kPi / 24 + 0.05;
        const IntegralImage ii(ramp(phi));
        const float theta = orientation(ii.view(), 100.0f, 100.0f, 2.0f);
        EXPECT_GE(theta, 0.0f);
        EXPECT_LT(theta, 2 * kPi);
        EXPECT_LT(angle_difference(theta, phi), 0.01) << "phi " << phi << " got " << theta;
    }
}

// Both descriptor kinds (params.h): Bay's SURF and M-SURF.
class DescriptorKinds : public ::testing::TestWithParam<DescriptorKind> {};

TEST_P(DescriptorKinds, RampGivesOnlyTheAlongComponentWhenAligned) {
    // Rotated to the gradient, every dd is positive and every dp is ~0 (up to the 8-bit
    // staircase of a slanted ramp): each sub-region is ~(a, 0, a, 0), and the vector is unit
    // length.
    const double phi = 0.7;
    const IntegralImage ii(ramp(phi));
    Keypoint kp;
    kp.x = 100.2f;
    kp.y = 99.7f;
    kp.scale = 1.6f;
    kp.orientation = static_cast<float>(phi);
    const std::array<float, 64> d = descriptor(ii.view(), kp, HaarMode::exact, GetParam());
    double norm2 = 0;
    for (float v : d) norm2 += v * v;
    EXPECT_NEAR(norm2, 1.0, 1e-5);
    // Measured on the staircase: |sum dp| <= 2 %, sum |dp| <= 4 % of sum dd.
    for (size_t r = 0; r < 16; ++r) {
        EXPECT_GT(d[4 * r], 0.005f);  // corner sub-regions carry little Gaussian weight
        EXPECT_FLOAT_EQ(d[4 * r], d[4 * r + 2]);
        EXPECT_LT(std::fabs(d[4 * r + 1]), 0.03f * d[4 * r]);
        EXPECT_LT(d[4 * r + 3], 0.05f * d[4 * r]);
    }
    // With the window turned to phi - 90 degrees the gradient lies along +dp (dp points 90
    // degrees counter-clockwise of dd, in image axes). The sub-region weights are symmetric
    // under the quarter turn, so the sums agree up to the staircase (measured <= 3.1 %).
    kp.orientation = static_cast<float>(phi - kPi / 2);
    const std::array<float, 64> q = descriptor(ii.view(), kp, HaarMode::exact, GetParam());
    for (size_t k = 0; k < 64; k += 4) {
        EXPECT_NEAR(q[k + 1], d[k], 0.05f * d[k]);
        EXPECT_NEAR(q[k + 3], d[k], 0.05f * d[k]);
        EXPECT_LT(std::fabs(q[k]), 0.03f * d[k]);
    }
}

INSTANTIATE_TEST_SUITE_P(Descriptor, DescriptorKinds, ::testing::Values(DescriptorKind::surf, DescriptorKind::msurf),
                         [](const auto& info) { return info.param == DescriptorKind::surf ? "Surf" : "Msurf"; });

// M-SURF's sub-regions overlap: a detail seen by one sub-region alone in SURF reaches its
// neighbours too, with a smaller weight. A bright square on a flat image, placed inside
// sub-region (row 1, column 1) of an upright window: SURF's other sub-regions see nothing of
// it beyond their own 5 samples, M-SURF's neighbours do.
TEST(Descriptor, MsurfSubRegionsOverlapTheirNeighbours) {
    cv::Mat img(200, 200, CV_8UC1, cv::Scalar(50));
    Keypoint kp;
    kp.x = 100, kp.y = 100, kp.scale = 2;
    // Sub-region (1, 1) spans samples 5..9 of 20, i.e. offsets -4.5s..-0.5s: x, y in 91..99.
    img(cv::Rect(93, 93, 4, 4)).setTo(250);
    const IntegralImage ii(img);
    const std::array<float, 64> surf = descriptor(ii.view(), kp, HaarMode::exact, DescriptorKind::surf);
    const std::array<float, 64> msurf = descriptor(ii.view(), kp, HaarMode::exact, DescriptorKind::msurf);
    auto energy = [](const std::array<float, 64>& d, int row, int column) {
        const size_t r = static_cast<size_t>(4 * (row * 4 + column));
        return d[r + 2] + d[r + 3];  // sum |dd| + sum |dp|
    };
    EXPECT_GT(energy(surf, 1, 1), 0.5f);
    EXPECT_GT(energy(msurf, 1, 1), 0.3f);
    // Sub-region (2, 2) starts at +0.5s = 101: SURF's wavelets of size 2s = 4 px at x >= 101
    // reach 99 at the least, the square ends at 96.5: nothing. M-SURF's 9 x 9 samples of
    // (2, 2) start 2 samples earlier, at 97: their wavelets reach 95 and see the square's edge.
    EXPECT_LT(energy(surf, 2, 2), 1e-6f);
    EXPECT_GT(energy(msurf, 2, 2), 0.001f);  // measured 0.0087: the far corner of a 2.5s Gaussian
    // Far corners see it in neither.
    EXPECT_LT(energy(surf, 3, 3), 1e-6f);
    EXPECT_LT(energy(msurf, 3, 3), 1e-6f);
}

// cv::rotate(ROTATE_90_CLOCKWISE) maps pixel (x, y) to (H-1-y, x): a rotation by +90 degrees in
// image axes, so orientations grow by pi/2. The crop is 641 x 513 so that W-1 and H-1 are
// multiples of 16, the largest sampling step: the rotated sample grids coincide with the
// originals and detection itself is exactly covariant (the box filters and border rule are
// symmetric); orientation and descriptor are computed with exact area integrals at real
// positions, so they are covariant up to float rounding.
TEST(Rotation, NinetyDegreesRotatesOrientationsAndKeepsDescriptors) {
    const cv::Mat graf = test::opencv_gray("graf1.png");
    ASSERT_FALSE(graf.empty());
    const cv::Mat img = graf(cv::Rect(80, 60, 641, 513)).clone();
    cv::Mat rotated;
    cv::rotate(img, rotated, cv::ROTATE_90_CLOCKWISE);

    Params params;
    params.threshold = threshold_for_count(img, 800, params);
    const Keypoints a = detect_and_describe(img, params);
    const Keypoints b = detect_and_describe(rotated, params);

    int paired = 0, within_bin = 0;
    std::vector<double> descriptor_distances;
    for (const Keypoint& p : a) {
        const float rx = static_cast<float>(img.rows - 1) - p.y, ry = p.x;
        const Keypoint* q = nullptr;
        for (const Keypoint& c : b)
            if (std::hypot(c.x - rx, c.y - ry) < 0.01 && std::fabs(c.scale - p.scale) < 1e-3f) q = &c;
        if (!q) continue;
        ++paired;
        if (angle_difference(q->orientation, p.orientation + kPi / 2) <= kPi / 18) ++within_bin;
        double d2 = 0;
        for (size_t k = 0; k < 64; ++k)
            d2 += (p.descriptor[k] - q->descriptor[k]) * (p.descriptor[k] - q->descriptor[k]);
        descriptor_distances.push_back(std::sqrt(d2));
    }
    ASSERT_GT(paired, 0);
    std::sort(descriptor_distances.begin(), descriptor_distances.end());
    const double median = descriptor_distances[descriptor_distances.size() / 2];
    const double p95 = descriptor_distances[descriptor_distances.size() * 95 / 100];
    const double max = descriptor_distances.back();
    std::cout << "rotation: " << a.size() << " / " << b.size() << " keypoints, " << paired << " paired, " << within_bin
              << " within pi/18, descriptor distance median " << median << " p95 " << p95 << " max " << max << "\n";
    EXPECT_EQ(a.size(), b.size());
    EXPECT_EQ(paired, static_cast<int>(a.size()));  // detection commutes with the rotation
    // Measured: every orientation exactly +pi/2 (to float rounding), descriptor distances
    // ~1e-5 (median 5e-6, max 3e-5); unit-length descriptors of unrelated points are ~1 apart.
    EXPECT_EQ(within_bin, paired);
    EXPECT_LT(median, 1e-4);
    EXPECT_LT(max, 1e-3);
}

// The same with rounded Haar wavelets (HaarMode::rounded): centring each wavelet on the pixel
// corner nearest to its sample is covariant under the quarter turn (the corner grid maps onto
// itself), except where a sample lies within float rounding of a pixel centre (the tie goes
// one way in both images) or where the paired keypoints' positions, which agree only to
// ~1e-3 px after interpolation, straddle a rounding boundary. Those samples move a whole
// pixel, so orientations and descriptors agree less tightly than in the exact mode.
TEST(Rotation, NinetyDegreesWithRoundedHaarWavelets) {
    const cv::Mat graf = test::opencv_gray("graf1.png");
    ASSERT_FALSE(graf.empty());
    const cv::Mat img = graf(cv::Rect(80, 60, 641, 513)).clone();
    cv::Mat rotated;
    cv::rotate(img, rotated, cv::ROTATE_90_CLOCKWISE);

    Params params;
    params.haar = HaarMode::rounded;
    params.threshold = threshold_for_count(img, 800, params);
    const Keypoints a = detect_and_describe(img, params);
    const Keypoints b = detect_and_describe(rotated, params);

    int paired = 0, within_bin = 0;
    std::vector<double> descriptor_distances, orientation_differences;
    for (const Keypoint& p : a) {
        const float rx = static_cast<float>(img.rows - 1) - p.y, ry = p.x;
        const Keypoint* q = nullptr;
        for (const Keypoint& c : b)
            if (std::hypot(c.x - rx, c.y - ry) < 0.01 && std::fabs(c.scale - p.scale) < 1e-3f) q = &c;
        if (!q) continue;
        ++paired;
        const double turn = angle_difference(q->orientation, p.orientation + kPi / 2);
        orientation_differences.push_back(turn);
        if (turn <= kPi / 18) ++within_bin;
        double d2 = 0;
        for (size_t k = 0; k < 64; ++k)
            d2 += (p.descriptor[k] - q->descriptor[k]) * (p.descriptor[k] - q->descriptor[k]);
        descriptor_distances.push_back(std::sqrt(d2));
    }
    ASSERT_GT(paired, 0);
    std::sort(descriptor_distances.begin(), descriptor_distances.end());
    std::sort(orientation_differences.begin(), orientation_differences.end());
    const size_t n = descriptor_distances.size();
    const double median = descriptor_distances[n / 2];
    const double p95 = descriptor_distances[n * 95 / 100];
    const double max = descriptor_distances.back();
    size_t exact_turns = 0;
    for (double t : orientation_differences) exact_turns += t < 1e-4;
    std::cout << "rotation (rounded Haar): " << a.size() << " / " << b.size() << " keypoints, " << paired << " paired, "
              << within_bin << " within pi/18, " << exact_turns << " within 1e-4 rad, orientation p95 "
              << orientation_differences[n * 95 / 100] << " max " << orientation_differences.back()
              << "; descriptor distance median " << median << " p95 " << p95 << " max " << max << "\n";
    RecordProperty("descriptor_distance_median", std::to_string(median));
    RecordProperty("descriptor_distance_max", std::to_string(max));
    EXPECT_EQ(a.size(), b.size());
    EXPECT_EQ(paired, static_cast<int>(a.size()));  // detection does not depend on the Haar mode
    // Measured: all 800 orientations within pi/18 of +pi/2 (799 within 1e-4 rad, the other
    // 0.005 rad off); descriptor distances median 1.3e-7, p95 3e-7, max 0.032 (one keypoint).
    EXPECT_EQ(within_bin, paired);
    EXPECT_LT(median, 1e-4);
    EXPECT_LT(p95, 1e-3);
    EXPECT_LT(max, 0.1);
}

}  // namespace
}  // namespace surfvp::surf
