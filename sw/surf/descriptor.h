#pragma once
// SURF-64 descriptor (paper §II, step 4; Bay et al. 2008 §4.2) and its M-SURF variant.
#include <array>
#include <cmath>
#include <cstddef>

#include "sw/surf/haar.h"
#include "sw/surf/integral_image.h"
#include "sw/surf/keypoint.h"
#include "sw/surf/params.h"

namespace surfvp::surf {

namespace descriptor_detail {

constexpr int kSamples = 20;       // 20s window, s apart
constexpr int kRegionSamples = 5;  // 4 x 4 sub-regions of 5 x 5
constexpr float kSigma = 3.3f;     // 3.3s
constexpr float kWaveletSize = 2;  // 2s

// Gaussian weight of sample (k, m), k along and m across the orientation, in units of s.
struct WeightTable {
    float w[kSamples][kSamples];
    WeightTable() {
        for (int m = 0; m < kSamples; ++m)
            for (int k = 0; k < kSamples; ++k) {
                const float u = k - 9.5f, v = m - 9.5f;
                w[m][k] = std::exp(-(u * u + v * v) / (2 * kSigma * kSigma));
            }
    }
};

inline float sample_offset(int k) { return k - (kSamples - 1) / 2.0f; }

constexpr int kMsurfSamples = 24;         // 4 sub-regions of 5 plus 2 on each side
constexpr int kMsurfRegion = 9;           // a sub-region's samples: its 5 and 2 of each neighbour
constexpr float kMsurfInnerSigma = 2.5f;  // in s
constexpr float kMsurfOuterSigma = 1.5f;  // in sub-regions

struct MsurfWeights {
    float inner[kMsurfRegion][kMsurfRegion];
    float outer[4][4];
    MsurfWeights() {
        for (int i = 0; i < kMsurfRegion; ++i)
            for (int j = 0; j < kMsurfRegion; ++j)
                inner[i][j] =
                    std::exp(-((i - 4) * (i - 4) + (j - 4) * (j - 4)) / (2 * kMsurfInnerSigma * kMsurfInnerSigma));
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) {
                const float u = a - 1.5f, v = b - 1.5f;
                outer[a][b] = std::exp(-(u * u + v * v) / (2 * kMsurfOuterSigma * kMsurfOuterSigma));
            }
    }
};

// Scales the 64 values to unit length (all zero stays zero).
inline void normalise(std::array<float, 64>& d) {
    double norm2 = 0;
    for (float x : d) norm2 += static_cast<double>(x) * x;
    if (norm2 > 0) {
        const float inv = static_cast<float>(1.0 / std::sqrt(norm2));
        for (float& x : d) x *= inv;
    }
}

}  // namespace descriptor_detail

namespace descriptor_detail {

// The descriptor proper, with the Haar wavelet pair at a sample position given by `haar`.
template <class Haar>
[[gnu::always_inline]] inline std::array<float, 64> describe_window(const Keypoint& kp, const Haar& haar) {
    static const WeightTable table;  // built once
    const float s = kp.scale;
    const float c = std::cos(kp.orientation), sn = std::sin(kp.orientation);
    std::array<float, 64> d{};
    for (int m = 0; m < kSamples; ++m) {
        const float v = sample_offset(m) * s;
        for (int k = 0; k < kSamples; ++k) {
            const float u = sample_offset(k) * s;
            const float px = kp.x + u * c - v * sn;
            const float py = kp.y + u * sn + v * c;
            const HaarResponse r = haar(px, py);
            const float w = table.w[m][k];
            const float dd = w * (r.dx * c + r.dy * sn);
            const float dp = w * (-r.dx * sn + r.dy * c);
            float* region = &d[static_cast<size_t>(4 * ((m / kRegionSamples) * 4 + k / kRegionSamples))];
            region[0] += dd;
            region[1] += dp;
            region[2] += std::fabs(dd);
            region[3] += std::fabs(dp);
        }
    }
    normalise(d);
    return d;
}

// M-SURF: 24 x 24 samples s apart (centres at (k - 11.5) s); sub-region (a, b) sums the 9 x 9
// samples 5a..5a+8 across, 5b..5b+8 along, each weighted by a Gaussian of sigma 2.5s about the
// sub-region's centre, then the sub-region by a Gaussian of sigma 1.5 sub-regions about the
// window's centre.
template <class Haar>
[[gnu::always_inline]] inline std::array<float, 64> describe_msurf(const Keypoint& kp, const Haar& haar) {
    static const MsurfWeights weights;
    const float s = kp.scale;
    const float c = std::cos(kp.orientation), sn = std::sin(kp.orientation);
    float dd[kMsurfSamples][kMsurfSamples], dp[kMsurfSamples][kMsurfSamples];
    for (int m = 0; m < kMsurfSamples; ++m) {
        const float v = (m - (kMsurfSamples - 1) / 2.0f) * s;
        for (int k = 0; k < kMsurfSamples; ++k) {
            const float u = (k - (kMsurfSamples - 1) / 2.0f) * s;
            const HaarResponse r = haar(kp.x + u * c - v * sn, kp.y + u * sn + v * c);
            dd[m][k] = r.dx * c + r.dy * sn;
            dp[m][k] = -r.dx * sn + r.dy * c;
        }
    }
    std::array<float, 64> d{};
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            float sum[4] = {};
            for (int i = 0; i < kMsurfRegion; ++i)
                for (int j = 0; j < kMsurfRegion; ++j) {
                    const float w = weights.inner[i][j];
                    const float x = w * dd[5 * a + i][5 * b + j], y = w * dp[5 * a + i][5 * b + j];
                    sum[0] += x;
                    sum[1] += y;
                    sum[2] += std::fabs(x);
                    sum[3] += std::fabs(y);
                }
            float* region = &d[static_cast<size_t>(4 * (a * 4 + b))];
            for (int q = 0; q < 4; ++q) region[q] = weights.outer[a][b] * sum[q];
        }
    normalise(d);
    return d;
}

}  // namespace descriptor_detail

// Descriptor of the square window of side 20s centred on (kp.x, kp.y) and rotated to
// kp.orientation. The window is 4 x 4 sub-regions of 5 x 5 samples spaced s (sample centres at
// (k - 9.5) s, k = 0..19, along and across the orientation). At each sample, Haar wavelets of
// size 2s give (dx, dy), which are rotated into the window frame: dd along the orientation, dp
// perpendicular to it (+90 degrees), and weighted by a Gaussian of sigma 3.3s centred on the
// point. Each sub-region contributes (sum dd, sum dp, sum |dd|, sum |dp|); sub-regions are in
// row-major order of the window (rows across, columns along the orientation). The 64 values
// are scaled to unit length (all zero for a perfectly flat window). Any integral-image view
// type (integral_image.h).
//
// `mode` (params.h): exact wavelets of size 2s at the real (rotated) sample positions, or
// rounded ones (haar_response_rounded) of size 2 round(s), OpenSURF's 2 fRound(scale),
// centred on the pixel corner nearest to each sample. Everything else is the same.
//
// `kind` (params.h): surf is the above (Bay et al.; the chip's software); msurf is M-SURF
// (Agrawal et al., ECCV 2008; OpenSURF's default): the window grows to 24s, each sub-region
// takes 9 x 9 samples (its own 5 x 5 and 2 of each neighbour's), weighted by a Gaussian of
// sigma 2.5s about its own centre instead of the one 3.3s Gaussian, and each sub-region's four
// sums are weighted by a Gaussian of sigma 1.5 sub-regions about the window's centre. A sample
// moving across a sub-region boundary then changes the descriptor gradually: measured on graf
// and the castle (docs/quality.md), matching precision rises by ~0.06.
template <class View>
std::array<float, 64> descriptor(const View& ii, const Keypoint& kp, HaarMode mode = HaarMode::exact,
                                 DescriptorKind kind = DescriptorKind::surf) {
    using namespace descriptor_detail;
    return with_haar(ii, mode, kWaveletSize * kp.scale, [&](const auto& haar) {
        return kind == DescriptorKind::msurf ? describe_msurf(kp, haar) : describe_window(kp, haar);
    });
}

}  // namespace surfvp::surf
