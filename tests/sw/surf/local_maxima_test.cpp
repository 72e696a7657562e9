// Non-maximum suppression and interpolation on hand-made response stacks.
#include <gtest/gtest.h>

#include <functional>

#include "sw/surf/interpolation.h"
#include "sw/surf/local_maxima.h"

namespace surfvp::surf {
namespace {

// One octave (octave index 1, step 2), 4 layers on a 20 x 16 grid, all samples valid except a
// one-sample frame, values from f(kx, ky, layer).
ResponseStack make_stack(const std::function<float(int, int, int)>& f) {
    ResponseStack stack;
    stack.width = 40;
    stack.height = 32;
    stack.octaves.resize(2);
    for (int o = 0; o < 2; ++o) {
        ResponseOctave& oct = stack.octaves[static_cast<size_t>(o)];
        oct.octave = o;
        oct.step = 1 << o;
        oct.cols = 40 >> o;
        oct.rows = 32 >> o;
        for (int i = 0; i < 4; ++i) {
            ResponseLayer layer;
            layer.filter_size = filter_size(o, i);
            layer.x_begin = 1;
            layer.x_end = oct.cols - 1;
            layer.y_begin = 1;
            layer.y_end = oct.rows - 1;
            layer.det.assign(static_cast<size_t>(oct.cols) * oct.rows, 0.0f);
            if (o == 1)
                for (int ky = 1; ky < oct.rows - 1; ++ky)
                    for (int kx = 1; kx < oct.cols - 1; ++kx)
                        layer.det[static_cast<size_t>(ky) * oct.cols + kx] = f(kx, ky, i);
            oct.layers.push_back(layer);
        }
    }
    return stack;
}

// A concave quadratic with its vertex at (cx, cy, cs) in sample units.
std::function<float(int, int, int)> peak(double cx, double cy, double cs, double top = 1000) {
    return [=](int kx, int ky, int layer) {
        const double dx = kx - cx, dy = ky - cy, ds = layer - cs;
        return static_cast<float>(top - 10 * dx * dx - 7 * dy * dy - 30 * ds * ds + 2 * dx * dy);
    };
}

TEST(LocalMaxima, FindsTheSinglePeakAboveThreshold) {
    const ResponseStack stack = make_stack(peak(8.2, 6.9, 1.3));
    const std::vector<LocalMaximum> maxima = find_local_maxima(stack, 500, 1);
    ASSERT_EQ(maxima.size(), 1u);
    EXPECT_EQ(maxima[0].octave, 1);
    EXPECT_EQ(maxima[0].layer, 1);
    EXPECT_EQ(maxima[0].kx, 8);
    EXPECT_EQ(maxima[0].ky, 7);
    EXPECT_TRUE(find_local_maxima(stack, 1000, 1).empty());  // response below the threshold
    EXPECT_EQ(find_local_maxima(stack, 500, 3).size(), 1u);
}

TEST(LocalMaxima, TiesAreNotMaxima) {
    // Two equal neighbouring samples: neither is strictly greater than all 26 neighbours.
    ResponseStack stack = make_stack(peak(8, 7, 1));
    ResponseOctave& oct = stack.octaves[1];
    oct.layers[1].det[static_cast<size_t>(7) * oct.cols + 9] = oct.at(1, 8, 7);
    EXPECT_TRUE(find_local_maxima(stack, 0, 1).empty());
}

TEST(LocalMaxima, NeighbourhoodMustBeInsideEveryLayersValidRange) {
    // The peak sits on the first valid sample of the layer above: not a candidate.
    ResponseStack stack = make_stack(peak(2, 7, 1));
    for (ResponseLayer& l : stack.octaves[1].layers) l.x_begin = 2;
    EXPECT_TRUE(find_local_maxima(stack, 0, 1).empty());
    for (ResponseLayer& l : stack.octaves[1].layers) l.x_begin = 1;
    EXPECT_EQ(find_local_maxima(stack, 0, 1).size(), 1u);
}

TEST(Interpolation, RecoversTheVertexOfAQuadratic) {
    const ResponseStack stack = make_stack(peak(8.2, 6.9, 1.3));
    const std::vector<LocalMaximum> maxima = find_local_maxima(stack, 0, 1);
    ASSERT_EQ(maxima.size(), 1u);
    const std::optional<Keypoint> kp = interpolate_maximum(stack, maxima[0], 0.5f);
    ASSERT_TRUE(kp.has_value());
    // Octave 1: step 2, filter spacing 12, interval 1 has L = 27.
    EXPECT_NEAR(kp->x, 8.2 * 2, 1e-3);
    EXPECT_NEAR(kp->y, 6.9 * 2, 1e-3);
    EXPECT_NEAR(kp->scale, 1.2 * (27 + 0.3 * 12) / 9, 1e-4);
    EXPECT_EQ(kp->response, stack.octaves[1].at(1, 8, 7));
}

TEST(Interpolation, RejectsOffsetsAboveTheLimit) {
    // The sampled maximum is at kx = 8 but the quadratic's vertex is 0.55 samples away: the
    // 3x3x3 fit lands outside +-0.5 (the paper's rule), inside +-1 (OpenCV's).
    ResponseStack stack = make_stack(peak(8.45, 7, 1));
    LocalMaximum m{1, 1, 8, 7, stack.octaves[1].at(1, 8, 7)};
    ASSERT_TRUE(interpolate_maximum(stack, m, 0.5f).has_value());
    stack = make_stack(peak(8.55, 7, 1));
    m.response = stack.octaves[1].at(1, 8, 7);
    EXPECT_FALSE(interpolate_maximum(stack, m, 0.5f).has_value());
    const std::optional<Keypoint> kp = interpolate_maximum(stack, m, 1.0f);
    ASSERT_TRUE(kp.has_value());
    EXPECT_NEAR(kp->x, 8.55 * 2, 1e-3);
    // The scale axis too: a vertex 0.7 intervals above the sampled layer.
    stack = make_stack(peak(8, 7, 1.7));
    m = {1, 1, 8, 7, stack.octaves[1].at(1, 8, 7)};
    EXPECT_FALSE(interpolate_maximum(stack, m, 0.5f).has_value());
    ASSERT_TRUE(interpolate_maximum(stack, m, 1.0f).has_value());
    EXPECT_NEAR(interpolate_maximum(stack, m, 1.0f)->scale, 1.2 * (27 + 0.7 * 12) / 9, 1e-4);
    stack = make_stack(peak(9.2, 7, 1));
    m = {1, 1, 8, 7, stack.octaves[1].at(1, 8, 7)};
    EXPECT_FALSE(interpolate_maximum(stack, m, 1.0f).has_value());
}

}  // namespace
}  // namespace surfvp::surf
