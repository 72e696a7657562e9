// Fast-Hessian determinants against a direct computation from pixel sums (paper eq. 3 with the
// box filters of Bay et al. 2008 written as per-pixel weights, no -3 trick, no integral image).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <opencv2/core.hpp>

#include "sw/surf/fast_hessian.h"

namespace surfvp::surf {
namespace {

cv::Mat random_image(int width, int height, unsigned seed) {
    cv::Mat img(height, width, CV_8UC1);
    cv::RNG rng(seed);
    rng.fill(img, cv::RNG::UNIFORM, 0, 256);
    return img;
}

// The three filters of size L as weights at offset (u, v) from the centre.
int weight_yy(int L, int u, int v) {  // lobes stacked vertically: +1, -2, +1
    const int l = L / 3, b = (L - 1) / 2;
    if (std::abs(u) > l - 1 || std::abs(v) > b) return 0;
    return std::abs(v) <= (l - 1) / 2 ? -2 : 1;
}
int weight_xx(int L, int u, int v) { return weight_yy(L, v, u); }
int weight_xy(int L, int u, int v) {  // +1 top-left and bottom-right, -1 the other two
    const int l = L / 3;
    if (u == 0 || v == 0 || std::abs(u) > l || std::abs(v) > l) return 0;
    return (u > 0) == (v > 0) ? 1 : -1;
}

struct Direct {
    long long dxx = 0, dyy = 0, dxy = 0;
    double det = 0;
};

Direct direct_hessian(const cv::Mat& img, int x, int y, int L) {
    Direct d;
    const int r = L / 2 + 1;
    for (int v = -r; v <= r; ++v)
        for (int u = -r; u <= r; ++u) {
            const int p = img.at<uint8_t>(y + v, x + u);
            d.dxx += weight_xx(L, u, v) * p;
            d.dyy += weight_yy(L, u, v) * p;
            d.dxy += weight_xy(L, u, v) * p;
        }
    const double area = static_cast<double>(L) * L;
    d.det = (d.dxx / area) * (d.dyy / area) - 0.81 * (d.dxy / area) * (d.dxy / area);
    return d;
}

TEST(FastHessian, FilterSizesFollowTheSurfPapers) {
    const int expected[4][4] = {{9, 15, 21, 27}, {15, 27, 39, 51}, {27, 51, 75, 99}, {51, 99, 147, 195}};
    for (int o = 0; o < 4; ++o)
        for (int i = 0; i < 4; ++i) EXPECT_EQ(filter_size(o, i), expected[o][i]) << o << "," << i;
    EXPECT_FLOAT_EQ(filter_scale(9), 1.2f);
    EXPECT_FLOAT_EQ(filter_scale(27), 3.6f);
    EXPECT_EQ(sample_step(3, 2), 16);
}

TEST(FastHessian, DeterminantAtRandomPointsMatchesDirectPixelSums) {
    const cv::Mat img = random_image(300, 260, 7);
    const IntegralImage ii(img);
    std::mt19937 rng(8);
    const int sizes[] = {9, 15, 21, 27, 39, 51, 75, 99, 147, 195};
    int checked = 0;
    for (int L : sizes) {
        for (int n = 0; n < 40; ++n) {
            const int x = std::uniform_int_distribution<int>(0, img.cols - 1)(rng);
            const int y = std::uniform_int_distribution<int>(0, img.rows - 1)(rng);
            if (!filter_inside(img.cols, img.rows, x, y, L)) continue;
            const Hessian h = hessian_at(ii.view(), x, y, L);
            const Direct d = direct_hessian(img, x, y, L);
            ASSERT_EQ(h.dxx, d.dxx) << "L=" << L;
            ASSERT_EQ(h.dyy, d.dyy) << "L=" << L;
            ASSERT_EQ(h.dxy, d.dxy) << "L=" << L;
            ASSERT_NEAR(h.det, d.det, 1e-5 * std::abs(d.det) + 1e-3) << "L=" << L;
            EXPECT_EQ(h.laplacian, d.dxx + d.dyy >= 0 ? 1 : -1);
            ++checked;
        }
    }
    EXPECT_GT(checked, 150);
}

TEST(FastHessian, BorderRuleKeepsFilterAndOnePixelInside) {
    // L = 9: b = 4, so x must lie in [5, width - 6].
    EXPECT_FALSE(filter_inside(100, 100, 4, 50, 9));
    EXPECT_TRUE(filter_inside(100, 100, 5, 50, 9));
    EXPECT_TRUE(filter_inside(100, 100, 94, 50, 9));
    EXPECT_FALSE(filter_inside(100, 100, 95, 50, 9));
    EXPECT_FALSE(filter_inside(100, 100, 50, 95, 9));
}

// The vectorised row computation and the layer reuse between octaves give the point-by-point
// reference values at every sample, on any number of threads; outside the valid range: 0.
void expect_stack_matches_reference(const cv::Mat& img, const Params& params, int threads) {
    const IntegralImage ii(img);
    const ResponseStack stack = compute_responses(ii.view(), params, threads);
    ASSERT_EQ(stack.octaves.size(), static_cast<size_t>(params.octaves));
    long valid = 0;
    for (const ResponseOctave& oct : stack.octaves) {
        EXPECT_EQ(oct.step, params.init_step << oct.octave);
        for (const ResponseLayer& layer : oct.layers)
            for (int ky = 0; ky < oct.rows; ++ky)
                for (int kx = 0; kx < oct.cols; ++kx) {
                    const float v = layer.det[static_cast<size_t>(ky) * oct.cols + kx];
                    const int x = kx * oct.step, y = ky * oct.step;
                    const bool inside =
                        kx >= layer.x_begin && kx < layer.x_end && ky >= layer.y_begin && ky < layer.y_end;
                    ASSERT_EQ(inside, filter_inside(img.cols, img.rows, x, y, layer.filter_size))
                        << "L=" << layer.filter_size << " at " << x << "," << y;
                    if (!inside) {
                        ASSERT_EQ(v, 0.0f);
                        continue;
                    }
                    ASSERT_EQ(v, hessian_at(ii.view(), x, y, layer.filter_size).det)
                        << "L=" << layer.filter_size << " at " << x << "," << y;
                    ++valid;
                }
    }
    EXPECT_GT(valid, 10000);
}

TEST(FastHessian, StackMatchesPointwiseReferenceStep1OneThread) {
    Params p;
    expect_stack_matches_reference(random_image(421, 333, 9), p, 1);
}

TEST(FastHessian, StackMatchesPointwiseReferenceStep2ThreeThreads) {
    Params p;
    p.init_step = 2;
    expect_stack_matches_reference(random_image(421, 333, 10), p, 3);
}

TEST(FastHessian, StackWithFiveIntervalsMatchesReference) {
    Params p;
    p.intervals = 5;
    p.octaves = 3;
    expect_stack_matches_reference(random_image(257, 300, 11), p, 2);
}

}  // namespace
}  // namespace surfvp::surf
