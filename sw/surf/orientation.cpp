#include "sw/surf/orientation.h"

#include <array>
#include <cmath>
#include <vector>

#include "sw/surf/haar.h"

namespace surfvp::surf {
namespace {

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

// The circular sampling grid with its Gaussian weights, built once.
const std::vector<Sample>& samples() {
    static const std::vector<Sample> grid = [] {
        std::vector<Sample> g;
        for (int j = -kRadius; j <= kRadius; ++j)
            for (int i = -kRadius; i <= kRadius; ++i)
                if (i * i + j * j < kRadius * kRadius)
                    g.push_back({i, j, std::exp(-(i * i + j * j) / (2 * kSigma * kSigma))});
        return g;
    }();
    return grid;
}

float wrap_angle(float a) {
    a = std::fmod(a, kTwoPi);
    return a < 0 ? a + kTwoPi : a;
}

}  // namespace

float orientation(const IntegralView& ii, float x, float y, float scale) {
    std::array<float, kBins> bin_dx{}, bin_dy{};
    for (const Sample& s : samples()) {
        const HaarResponse r = haar_response(ii, x + s.i * scale, y + s.j * scale, kWaveletSize * scale);
        const float dx = s.weight * r.dx, dy = s.weight * r.dy;
        if (dx == 0 && dy == 0) continue;
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

}  // namespace surfvp::surf
