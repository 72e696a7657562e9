#include "sw/surf/orientation.h"

namespace surfvp::surf::orientation_detail {

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

}  // namespace surfvp::surf::orientation_detail
