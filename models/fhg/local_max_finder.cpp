#include "local_max_finder.h"

#include <algorithm>
#include <limits>

namespace surfvp::fhg {
namespace {

// Octave 1: the determinant of size index s (0..3) at block pixel (px, py) is record[4 s + 2 py + px].
int32_t octave1(const int32_t* record, int s, int px, int py) { return record[4 * s + 2 * py + px]; }

// Octave 2's four scales at a block's pixel (0, 0): sizes 15, 27 (shared with octave 1), 39, 51.
constexpr int kOctave2Index[4] = {4 * 1, 4 * 3, 16, 17};

}  // namespace

uint32_t pack_candidate(const Candidate& c) {
    return 1u << 31 | uint32_t(c.octave() == 2) << 27 | uint32_t(c.size_index & 7) << 24 | uint32_t(c.y & 0xFFF) << 12 |
           uint32_t(c.x & 0xFFF);
}

Candidate unpack_candidate(uint32_t word) {
    return {int(word & 0xFFF), int((word >> 12) & 0xFFF), int((word >> 24) & 7)};
}

void LocalMaxFinder::block(const int32_t* current, const int32_t* left, int bx, int by,
                           std::vector<Candidate>& out) const {
    // Octave 1: neighbours at x - 1 .. x + 1 within the current and left blocks, same two rows.
    auto value = [&](int nx, int ny, int s, bool& available) -> int32_t {
        // nx in -2..1 relative to the current block's column 0; ny in 0..1.
        available = ny >= 0 && ny <= 1 && nx >= (left ? -2 : 0) && nx <= 1;
        if (!available) return 0;
        return nx >= 0 ? octave1(current, s, nx, ny) : octave1(left, s, nx + 2, ny);
    };
    for (int s = 1; s <= 2; ++s)
        for (int py = 0; py < 2; ++py)
            for (int px = 0; px < 2; ++px) {
                const int32_t v = octave1(current, s, px, py);
                if (v <= threshold_) continue;
                bool maximum = true;
                for (int ds = -1; ds <= 1 && maximum; ++ds)
                    for (int dy = -1; dy <= 1 && maximum; ++dy)
                        for (int dx = -1; dx <= 1 && maximum; ++dx) {
                            if (!ds && !dy && !dx) continue;
                            bool available = false;
                            const int32_t n = value(px + dx, py + dy, s + ds, available);
                            maximum = !available || v > n;
                        }
                if (maximum) out.push_back({2 * bx + px, 2 * by + py, s});
            }
    // Octave 2: one sample per block; its only in-window neighbour position is the left block's.
    for (int s = 1; s <= 2; ++s) {
        const int32_t v = current[kOctave2Index[s]];
        if (v <= threshold_) continue;
        bool maximum = v > current[kOctave2Index[s - 1]] && v > current[kOctave2Index[s + 1]];
        if (left)
            for (int ds = -1; ds <= 1 && maximum; ++ds) maximum = v > left[kOctave2Index[s + ds]];
        if (maximum) out.push_back({2 * bx, 2 * by, s == 1 ? 3 : 4});
    }
}

namespace {

// The largest of the determinants block() tests against the threshold: with none above it,
// the block marks nothing.
int32_t tested_peak(const int32_t* record) {
    int32_t peak = std::numeric_limits<int32_t>::min();
    for (int k = 0; k < kDeterminantsPerBlock; ++k)
        if (tested_by_finder(k)) peak = std::max(peak, record[k]);
    return peak;
}

}  // namespace

void LocalMaxFinder::block_row(const int32_t* records, int blocks, int by, std::vector<Candidate>& out) const {
    // Few blocks hold a determinant above the threshold (a frame's ~100 keypoints come from a
    // few thousand candidates among ~200 thousand blocks): the neighbour tests run for those.
    for (int bx = 0; bx < blocks; ++bx) {
        const int32_t* record = records + bx * kDeterminantsPerBlock;
        if (tested_peak(record) > threshold_) block(record, bx ? record - kDeterminantsPerBlock : nullptr, bx, by, out);
    }
}

}  // namespace surfvp::fhg
