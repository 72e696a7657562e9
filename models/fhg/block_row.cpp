#include "block_row.h"

#include <cstring>
#include <immintrin.h>

#include "fhg_regs.h"

namespace surfvp::fhg {

namespace {

// Every block's record as the writer sends it: four-byte determinants big-endian, octave 1's
// pixel pairs eight bytes at a time (record positions 4 i + 2 py and the next). The stores are
// non-temporal (a frame's 14 MB of determinants is read back long after, if at all: writing it
// through the cache read each line from memory first), so the caller fences before it hands
// the row on.
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"))) void store_records_be32(
    const HessianCore::Lines& lines, uint8_t* row) {
    const int32_t* pairs[8];  // local copies: the byte stores below may alias anything
    for (int pair = 0; pair < 8; ++pair) pairs[pair] = lines.octave1[pair / 2][pair % 2];
    const int32_t *octave2_a = lines.octave2[0], *octave2_b = lines.octave2[1];
    for (int bx = 0; bx < lines.blocks; ++bx, row += kDeterminantsPerBlock * 4) {
        uint64_t record[kDeterminantsPerBlock / 2];
        for (int pair = 0; pair < 8; ++pair) {
            uint64_t two;
            std::memcpy(&two, pairs[pair] + 2 * bx, 8);
            two = __builtin_bswap64(two);
            record[pair] = two >> 32 | two << 32;  // each word swapped in its own place
        }
        record[8] =
            uint64_t(__builtin_bswap32(uint32_t(octave2_b[bx]))) << 32 | __builtin_bswap32(uint32_t(octave2_a[bx]));
        for (int q = 0; q < 9; ++q)
            _mm_stream_si64(reinterpret_cast<long long*>(row + 8 * q), static_cast<long long>(record[q]));
    }
}

void store_records(const HessianCore::Lines& lines, uint32_t det_bytes, uint8_t* row) {
    if (det_bytes == 4) {
        store_records_be32(lines, row);
        _mm_sfence();  // the streamed stores are seen before whatever publishes the row
        return;
    }
    for (int bx = 0; bx < lines.blocks; ++bx)
        for (int k = 0; k < kDeterminantsPerBlock; ++k, row += det_bytes)
            fhg_regs::store_det(row, lines.at(bx, k), det_bytes);
}

}  // namespace

std::vector<Candidate> block_row(const HessianCore& core, const IntegralView& lines, int by, int32_t threshold,
                                 uint32_t det_bytes, uint8_t* row) {
    thread_local std::vector<int32_t> peaks;
    peaks.resize(size_t(lines.width + 1) / 2);
    const HessianCore::Lines dets = core.block_row_lines(lines, by, peaks.data());
    store_records(dets, det_bytes, row);
    // LocalMaxFinder's block row: few blocks hold a determinant above the threshold (a frame's
    // ~100 keypoints come from a few thousand candidates among ~200 thousand blocks).
    const LocalMaxFinder finder(threshold);
    std::vector<Candidate> found;
    for (int bx = 0; bx < dets.blocks; ++bx) {
        if (peaks[size_t(bx)] <= threshold) continue;
        int32_t current[kDeterminantsPerBlock], left[kDeterminantsPerBlock];
        dets.record(bx, current);
        if (bx) dets.record(bx - 1, left);
        finder.block(current, bx ? left : nullptr, bx, by, found);
    }
    return found;
}

std::vector<Candidate> block_row(const std::vector<int32_t>& records, int by, int32_t threshold, uint32_t det_bytes,
                                 uint8_t* row) {
    fhg_regs::store_dets(row, records.data(), records.size(), det_bytes);
    std::vector<Candidate> found;
    LocalMaxFinder(threshold).block_row(records.data(), int(records.size()) / kDeterminantsPerBlock, by, found);
    return found;
}

}  // namespace surfvp::fhg
