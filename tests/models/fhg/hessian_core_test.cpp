// HessianCore: box sums against pixel sums, the fast row path against the per-block path,
// and the integer determinants against the float formula on a real image.
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "models/fhg/hessian_core.h"
#include "test_images.h"

namespace surfvp::fhg {
namespace {

using test::Integral;
using test::integral_of;

int64_t pixel_sum(const cv::Mat& image, int x0, int y0, int x1, int y1) {
    int64_t s = 0;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) s += image.at<uint8_t>(y, x);
    return s;
}

int64_t brute(const cv::Mat& image, int x, int y, int size, Response r) {
    int64_t s = 0;
    for (const Box& b : filter_boxes(size, r)) s += b.weight * pixel_sum(image, x + b.x0, y + b.y0, x + b.x1, y + b.y1);
    return s;
}

TEST(HessianCore, BoxSumsEqualPixelSums) {
    const cv::Mat image = test::random_image(120, 110, 7);
    const Integral ii = integral_of(image);
    const HessianCore core(Precision{});
    std::mt19937 rng(11);
    for (int size : kSizes)
        for (int trial = 0; trial < 40; ++trial) {
            const int b = (size - 1) / 2;
            const int x = b + int(rng() % (120 - 2 * b)), y = b + int(rng() % (110 - 2 * b));
            const auto s = core.sums(ii.view, x, y, size);
            ASSERT_EQ(s.xx, brute(image, x, y, size, Response::xx)) << size << " at " << x << "," << y;
            ASSERT_EQ(s.yy, brute(image, x, y, size, Response::yy));
            ASSERT_EQ(s.xy, brute(image, x, y, size, Response::xy));
            // The -3 trick gives Bay's three lobes weighted 1, -2, 1.
            const int l = size / 3;
            const int64_t lobes = pixel_sum(image, x - b, y - l + 1, x - b + l - 1, y + l - 1) -
                                  2 * pixel_sum(image, x - b + l, y - l + 1, x - b + 2 * l - 1, y + l - 1) +
                                  pixel_sum(image, x - b + 2 * l, y - l + 1, x + b, y + l - 1);
            ASSERT_EQ(s.xx, lobes);
        }
}

TEST(HessianCore, FiltersReadA52By52Window) {
    int min_x = 0, max_x = 0, min_y = 0, max_y = 0, reads = 0;
    for (int k = 0; k < kDeterminantsPerBlock; ++k) {
        const BlockDeterminant d = block_determinant(k);
        for (const Read& r : filter_reads(d.size)) {
            min_x = std::min(min_x, d.px + r.dx), max_x = std::max(max_x, d.px + r.dx);
            min_y = std::min(min_y, d.py + r.dy), max_y = std::max(max_y, d.py + r.dy);
            ++reads;
        }
    }
    EXPECT_EQ(reads, 18 * 32);
    EXPECT_EQ(max_x - min_x + 1, kWindow);
    EXPECT_EQ(max_y - min_y + 1, kWindow);
    EXPECT_EQ(min_y, -kReachBefore);
    EXPECT_EQ(max_y, kReachAfter);
}

// The row path (a box's corners at once, finished in double where exact) against the
// determinant of each block alone, at the default precision, at one too wide for double
// (finished in int64) and at one whose accumulators wrap.
TEST(HessianCore, BlockRowEqualsPerBlockDeterminantsIncludingBorders) {
    Precision wide;
    wide.accumulator_bits = 32, wide.response_bits = 32, wide.weight_frac_bits = 20;
    Precision wrapping;
    wrapping.accumulator_bits = 16, wrapping.response_bits = 12, wrapping.det_bits = 20;
    for (const Precision& precision : {Precision{}, wide, wrapping})
        for (auto [w, h] : {std::pair{131, 97}, std::pair{64, 60}, std::pair{53, 52}}) {
            const Integral ii = integral_of(test::random_image(w, h, unsigned(w)));
            const HessianCore core(precision);
            const int blocks = (w + 1) / 2;
            std::vector<int32_t> row(size_t(blocks) * kDeterminantsPerBlock);
            for (int by = 0; by < (h + 1) / 2; ++by) {
                core.block_row(ii.view, by, row.data());
                for (int bx = 0; bx < blocks; ++bx) {
                    const auto expected = core.block(ii.view, bx, by);
                    for (int k = 0; k < kDeterminantsPerBlock; ++k)
                        ASSERT_EQ(row[size_t(bx) * kDeterminantsPerBlock + k], expected[k])
                            << w << "x" << h << " block " << bx << "," << by << " k " << k << " accumulator "
                            << precision.accumulator_bits;
                }
            }
        }
}

TEST(HessianCore, OutsideTheImageIsZero) {
    const Integral ii = integral_of(test::random_image(80, 80, 5));
    const HessianCore core(Precision{});
    EXPECT_NE(core.determinant(ii.view, 25, 40, 51), 0);  // b = 25: x = 25 is the first that fits
    EXPECT_NE(core.determinant(ii.view, 54, 54, 51), 0);  // 54 + 25 = 79, the last column
    EXPECT_EQ(core.determinant(ii.view, 24, 40, 51), 0);
    EXPECT_EQ(core.determinant(ii.view, 40, 55, 51), 0);  // 55 + 25 > 79
}

double float_det(const HessianCore::Sums& s, int size) {
    const double a = double(size) * size;
    const double xx = s.xx / a, yy = s.yy / a, xy = s.xy / a;
    return xx * yy - 0.81 * xy * xy;
}

// Determinants of graf1 at 1024x768 (every third pixel, every size) against the float
// formula on the same box sums: the error the fixed-point path adds.
TEST(HessianCore, DeterminantsTrackTheFloatFormulaOnARealImage) {
    const cv::Mat image = test::graf_1024x768();
    ASSERT_FALSE(image.empty());
    const Integral ii = integral_of(image);
    const HessianCore core(Precision{});
    std::vector<double> abs_errors, rel_10, rel_100;
    for (int size : kSizes) {
        const int b = (size - 1) / 2;
        for (int y = b; y < image.rows - b; y += 3)
            for (int x = b; x < image.cols - b; x += 3) {
                const double reference = float_det(core.sums(ii.view, x, y, size), size);
                const double err = std::abs(core.to_float(core.determinant(ii.view, x, y, size)) - reference);
                abs_errors.push_back(err);
                if (std::abs(reference) >= 10) rel_10.push_back(err / std::abs(reference));
                if (std::abs(reference) >= 100) rel_100.push_back(err / std::abs(reference));
            }
    }
    auto quantile = [](std::vector<double> v, double q) {
        std::sort(v.begin(), v.end());
        return v[size_t(q * (v.size() - 1))];
    };
    std::printf("determinant error vs float (%zu): |error| median %.2g, p99 %.2g, max %.3g (threshold units)\n",
                abs_errors.size(), quantile(abs_errors, 0.5), quantile(abs_errors, 0.99), quantile(abs_errors, 1));
    std::printf("relative error, |det| >= 10 (%zu): p99 %.2g, max %.3g; |det| >= 100 (%zu): p99 %.2g, max %.3g\n",
                rel_10.size(), quantile(rel_10, 0.99), quantile(rel_10, 1), rel_100.size(), quantile(rel_100, 0.99),
                quantile(rel_100, 1));
    ASSERT_GT(rel_100.size(), 1000u);
    EXPECT_LT(quantile(abs_errors, 1), 0.15);  // response quantum 2^-9 times responses up to ~100
    EXPECT_LT(quantile(rel_10, 1), 0.01);
    EXPECT_LT(quantile(rel_100, 1), 1e-3);
}

TEST(HessianCore, NarrowDeterminantWordsSaturate) {
    // A white 5x5 square on black: at its centre, size 9 gives Dxx = Dyy = -5100, det ~ 3964.
    cv::Mat image(40, 40, CV_8UC1, cv::Scalar(0));
    image(cv::Rect(18, 18, 5, 5)).setTo(255);
    const Integral ii = integral_of(image);
    EXPECT_NEAR(HessianCore(Precision{}).to_float(HessianCore(Precision{}).determinant(ii.view, 20, 20, 9)),
                (5100.0 / 81) * (5100.0 / 81), 0.1);
    Precision p;
    p.det_bits = 16;
    p.det_frac_bits = 4;  // the largest 16-bit word is 2047.9375
    const HessianCore narrow(p);
    EXPECT_EQ(narrow.determinant(ii.view, 20, 20, 9), 32767);
}

TEST(HessianCore, ImpossiblePrecisionIsRefused) {
    Precision p;
    p.det_frac_bits = 19;  // more than 2 x 9 fraction bits of the product
    EXPECT_THROW(HessianCore{p}, std::invalid_argument);
    p = Precision{};
    p.accumulator_bits = 40;
    EXPECT_THROW(HessianCore{p}, std::invalid_argument);
}

}  // namespace
}  // namespace surfvp::fhg
