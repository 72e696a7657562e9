#include "sw/surf/twins.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace surfvp::surf {
namespace {

// Keypoints by the whole pixel they lie in: a twin lies in the same cell or a neighbour.
class Grid {
public:
    void add(const Keypoint& kp, size_t index) { cells_[key(cell(kp.x), cell(kp.y))].push_back(index); }
    template <typename Visit>
    void around(const Keypoint& kp, Visit visit) const {
        const long cx = cell(kp.x), cy = cell(kp.y);
        for (long y = cy - 1; y <= cy + 1; ++y)
            for (long x = cx - 1; x <= cx + 1; ++x)
                if (const auto it = cells_.find(key(x, y)); it != cells_.end())
                    for (size_t i : it->second) visit(i);
    }

private:
    static long cell(float v) { return long(std::floor(v)); }
    static long long key(long x, long y) { return (static_cast<long long>(y) << 32) ^ (x & 0xffffffffLL); }
    std::unordered_map<long long, std::vector<size_t>> cells_;
};

}  // namespace

bool twins(const Keypoint& a, const Keypoint& b) {
    const float dx = a.x - b.x, dy = a.y - b.y;
    const float ratio = std::max(a.scale, b.scale) / std::min(a.scale, b.scale);
    return dx * dx + dy * dy <= kTwinDistancePx * kTwinDistancePx && ratio < kTwinScaleRatio;
}

void drop_twins(Keypoints& keypoints) {
    std::vector<size_t> strongest(keypoints.size());
    std::iota(strongest.begin(), strongest.end(), size_t(0));
    std::stable_sort(strongest.begin(), strongest.end(),
                     [&](size_t a, size_t b) { return keypoints[a].response > keypoints[b].response; });
    std::vector<bool> keep(keypoints.size(), false);
    Grid kept;
    for (size_t i : strongest) {
        bool twin = false;
        kept.around(keypoints[i], [&](size_t k) { twin = twin || twins(keypoints[i], keypoints[k]); });
        if (twin) continue;
        keep[i] = true;
        kept.add(keypoints[i], i);
    }
    size_t out = 0;
    for (size_t i = 0; i < keypoints.size(); ++i)
        if (keep[i]) keypoints[out++] = keypoints[i];
    keypoints.resize(out);
}

double twin_share(const Keypoints& keypoints) {
    if (keypoints.size() < 2) return 0;
    Grid all;
    for (size_t i = 0; i < keypoints.size(); ++i) all.add(keypoints[i], i);
    size_t with_twin = 0;
    for (size_t i = 0; i < keypoints.size(); ++i) {
        bool twin = false;
        all.around(keypoints[i], [&](size_t k) { twin = twin || (k != i && twins(keypoints[i], keypoints[k])); });
        with_twin += twin;
    }
    return double(with_twin) / double(keypoints.size());
}

}  // namespace surfvp::surf
