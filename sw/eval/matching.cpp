#include "sw/eval/matching.h"

#include <cmath>
#include <limits>

namespace surfvp::eval {

namespace {

double squared_distance(const surf::Keypoint& a, const surf::Keypoint& b) {
    // Accumulated in double so the result does not depend on vectorisation order.
    double sum = 0;
    for (std::size_t i = 0; i < a.descriptor.size(); ++i) {
        double d = static_cast<double>(a.descriptor[i]) - static_cast<double>(b.descriptor[i]);
        sum += d * d;
    }
    return sum;
}

bool eligible(const surf::Keypoint& a, const surf::Keypoint& b, const RatioTestOptions& options) {
    if (options.same_laplacian && a.laplacian != b.laplacian) return false;
    if (options.search_radius) {
        double dx = static_cast<double>(b.x) - a.x, dy = static_cast<double>(b.y) - a.y;
        if (dx * dx + dy * dy > *options.search_radius * *options.search_radius) return false;
    }
    return true;
}

}  // namespace

double descriptor_distance(const surf::Keypoint& a, const surf::Keypoint& b) {
    return std::sqrt(squared_distance(a, b));
}

std::vector<Candidate> ratio_test_candidates(const surf::Keypoints& a, const surf::Keypoints& b,
                                             const RatioTestOptions& options) {
    constexpr double kNone = std::numeric_limits<double>::infinity();
    std::vector<Candidate> candidates;
    for (std::size_t i = 0; i < a.size(); ++i) {
        double best = kNone, second = kNone;
        std::size_t best_index = 0;
        for (std::size_t j = 0; j < b.size(); ++j) {
            if (!eligible(a[i], b[j], options)) continue;
            double d = squared_distance(a[i], b[j]);
            if (d < best) {
                second = best;
                best = d;
                best_index = j;
            } else if (d < second) {
                second = d;
            }
        }
        if (second == kNone) continue;  // fewer than two eligible features
        double nearest = std::sqrt(best), next = std::sqrt(second);
        if (nearest < options.ratio * next) {
            candidates.push_back({i, best_index, nearest, next});
        }
    }
    return candidates;
}

}  // namespace surfvp::eval
