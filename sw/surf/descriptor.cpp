#include "sw/surf/descriptor.h"

#include <cmath>

#include "sw/surf/haar.h"

namespace surfvp::surf {
namespace {

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

float sample_offset(int k) { return k - (kSamples - 1) / 2.0f; }

}  // namespace

std::array<float, 64> descriptor(const IntegralView& ii, const Keypoint& kp) {
    static const WeightTable weights;
    const float s = kp.scale;
    const float c = std::cos(kp.orientation), sn = std::sin(kp.orientation);
    std::array<float, 64> d{};
    for (int m = 0; m < kSamples; ++m) {
        const float v = sample_offset(m) * s;
        for (int k = 0; k < kSamples; ++k) {
            const float u = sample_offset(k) * s;
            const float px = kp.x + u * c - v * sn;
            const float py = kp.y + u * sn + v * c;
            const HaarResponse r = haar_response(ii, px, py, kWaveletSize * s);
            const float w = weights.w[m][k];
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

}  // namespace surfvp::surf
