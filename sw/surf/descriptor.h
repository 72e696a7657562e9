#pragma once
// SURF-64 descriptor (paper §II, step 4; Bay et al. 2008 §4.2).
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
    double norm2 = 0;
    for (float x : d) norm2 += static_cast<double>(x) * x;
    if (norm2 > 0) {
        const float inv = static_cast<float>(1.0 / std::sqrt(norm2));
        for (float& x : d) x *= inv;
    }
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
template <class View>
std::array<float, 64> descriptor(const View& ii, const Keypoint& kp, HaarMode mode = HaarMode::exact) {
    using namespace descriptor_detail;
    if (mode == HaarMode::rounded) {
        const int half = haar_detail::rounded_half(kWaveletSize / 2 * kp.scale);
        return describe_window(kp, [&](float px, float py) { return haar_response_rounded(ii, px, py, half); });
    }
    const float size = kWaveletSize * kp.scale;
    return describe_window(kp, [&](float px, float py) { return haar_response(ii, px, py, size); });
}

}  // namespace surfvp::surf
