#include "sw/surf/local_maxima.h"

#include <algorithm>

#include "sw/surf/parallel.h"

namespace surfvp::surf {
namespace {

bool beats_neighbours(const ResponseOctave& oct, int layer, int kx, int ky, float v) {
    for (int dl : {0, -1, 1}) {  // own layer first: it rejects most candidates
        const float* rows = oct.layers[static_cast<size_t>(layer + dl)].det.data();
        for (int dy = -1; dy <= 1; ++dy) {
            const float* row = rows + static_cast<size_t>(ky + dy) * oct.cols + kx;
            for (int dx = -1; dx <= 1; ++dx) {
                if (dl == 0 && dy == 0 && dx == 0) continue;
                if (!(v > row[dx])) return false;
            }
        }
    }
    return true;
}

// Sample range where the 3x3x3 neighbourhood around `layer` is entirely valid.
struct Range {
    int x_begin, x_end, y_begin, y_end;
};

Range candidate_range(const ResponseOctave& oct, int layer) {
    Range r{0, oct.cols, 0, oct.rows};
    for (int dl = -1; dl <= 1; ++dl) {
        const ResponseLayer& l = oct.layers[static_cast<size_t>(layer + dl)];
        r.x_begin = std::max(r.x_begin, l.x_begin + 1);
        r.x_end = std::min(r.x_end, l.x_end - 1);
        r.y_begin = std::max(r.y_begin, l.y_begin + 1);
        r.y_end = std::min(r.y_end, l.y_end - 1);
    }
    return r;
}

void scan_rows(const ResponseOctave& oct, int layer, const Range& r, float threshold, int row_begin, int row_end,
               std::vector<LocalMaximum>& out) {
    const std::vector<float>& det = oct.layers[static_cast<size_t>(layer)].det;
    for (int ky = std::max(row_begin, r.y_begin); ky < std::min(row_end, r.y_end); ++ky) {
        const float* row = det.data() + static_cast<size_t>(ky) * oct.cols;
        for (int kx = r.x_begin; kx < r.x_end; ++kx) {
            const float v = row[kx];
            if (v > threshold && beats_neighbours(oct, layer, kx, ky, v)) out.push_back({oct.octave, layer, kx, ky, v});
        }
    }
}

}  // namespace

std::vector<LocalMaximum> find_local_maxima(const ResponseStack& stack, float threshold, int threads) {
    std::vector<LocalMaximum> maxima;
    for (const ResponseOctave& oct : stack.octaves) {
        for (int layer = 1; layer + 1 < static_cast<int>(oct.layers.size()); ++layer) {
            const Range r = candidate_range(oct, layer);
            if (r.x_begin >= r.x_end || r.y_begin >= r.y_end) continue;
            const int chunks = std::max(1, std::min(threads, r.y_end - r.y_begin));
            std::vector<std::vector<LocalMaximum>> found(static_cast<size_t>(chunks));
            parallel_for(chunks, chunks, [&](int c, int) {
                const int rows = r.y_end - r.y_begin;
                const int begin = r.y_begin + rows * c / chunks;
                const int end = r.y_begin + rows * (c + 1) / chunks;
                scan_rows(oct, layer, r, threshold, begin, end, found[static_cast<size_t>(c)]);
            });
            for (const auto& part : found) maxima.insert(maxima.end(), part.begin(), part.end());
        }
    }
    return maxima;
}

}  // namespace surfvp::surf
