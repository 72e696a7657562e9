#pragma once
// Orientation assignment (paper §II, step 3; Bay et al. 2008 §4.1).
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "sw/surf/haar.h"
#include "sw/surf/integral_image.h"
#include "sw/surf/keypoint.h"
#include "sw/surf/params.h"

namespace surfvp::surf {

namespace orientation_detail {

constexpr float kTwoPi = 6.28318530717958647692f;
constexpr int kRadius = 6;         // 6s
constexpr float kSigma = 2.5f;     // 2.5s
constexpr float kWaveletSize = 4;  // 4s
constexpr int kBins = 36;          // pi/18 each
constexpr int kWindowBins = 6;     // pi/3

struct Sample {
    int i, j;  // offset in units of s
    float weight;
};

// The circular sampling grid (109 points) with its Gaussian weights, built once.
const std::vector<Sample>& samples();

inline float wrap_angle(float a) {
    a = std::fmod(a, kTwoPi);
    return a < 0 ? a + kTwoPi : a;
}

// The orientation proper, with the Haar wavelet pair at a sample position given by `haar`.
template <class Haar>
[[gnu::always_inline]] inline float dominant_direction(float x, float y, float scale, const Haar& haar, int* angles) {
    std::array<float, kBins> bin_dx{}, bin_dy{};
    for (const Sample& s : samples()) {
        const HaarResponse r = haar(x + s.i * scale, y + s.j * scale);
        const float dx = s.weight * r.dx, dy = s.weight * r.dy;
        if (dx == 0 && dy == 0) continue;
        if (angles) ++*angles;
        int bin = static_cast<int>(wrap_angle(std::atan2(dy, dx)) * (kBins / kTwoPi));
        if (bin >= kBins) bin = kBins - 1;  // an angle that rounds up to 2 pi
        bin_dx[static_cast<size_t>(bin)] += dx;
        bin_dy[static_cast<size_t>(bin)] += dy;
    }
    float best_len2 = 0, best_dx = 0, best_dy = 0;
    for (int start = 0; start < kBins; ++start) {
        float sx = 0, sy = 0;
        for (int k = 0; k < kWindowBins; ++k) {
            const size_t b = static_cast<size_t>((start + k) % kBins);
            sx += bin_dx[b];
            sy += bin_dy[b];
        }
        if (sx * sx + sy * sy > best_len2) {
            best_len2 = sx * sx + sy * sy;
            best_dx = sx;
            best_dy = sy;
        }
    }
    return best_len2 > 0 ? wrap_angle(std::atan2(best_dy, best_dx)) : 0.0f;
}

}  // namespace orientation_detail

// Dominant direction of the interest point at (x, y) with scale s, radians in [0, 2 pi),
// measured from +x towards +y in image axes (x right, y down): atan2(sum dy, sum dx).
//
// Haar wavelets of size 4s are sampled every s inside a circle of radius 6s (the 109 grid
// points with i^2 + j^2 < 36), weighted by a Gaussian of sigma 2.5s centred on the point. A
// window of pi/3 slides around the circle in steps of pi/18; the window whose summed
// (dx, dy) is longest gives the direction. Because both the width and the step are multiples
// of pi/18, responses are summed into 36 bins of pi/18 first and a window is 6 adjacent bins,
// which is exactly the sliding-window sum. Any integral-image view type (integral_image.h).
//
// `mode` (params.h): exact wavelets of size 4s at the real sample positions, or rounded ones
// (haar_response_rounded) of size 2 round(2s), the even whole size nearest to 4s, centred on
// the pixel corner nearest to each sample. OpenSURF uses 4 round(s), up to 2 px from 4s
// (s = 1.4: 4 vs 5.6); 2 round(2s) is within 1 px. Everything else is the same. `angles`,
// when given, counts the samples whose angle was computed (not both responses 0): the
// software stage's cost model prices them (sw/cpu_cost/work_units.h).
template <class View>
float orientation(const View& ii, float x, float y, float scale, HaarMode mode = HaarMode::exact,
                  int* angles = nullptr) {
    using namespace orientation_detail;
    return with_haar(ii, mode, kWaveletSize * scale,
                     [&](const auto& haar) { return dominant_direction(x, y, scale, haar, angles); });
}

}  // namespace surfvp::surf
