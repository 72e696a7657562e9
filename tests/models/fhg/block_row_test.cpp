// fhg::block_row (what the FHG's worker and direct mode run) against the plain path it
// replaces: HessianCore::block_row's records stored one by one with store_det, and
// LocalMaxFinder::block_row's candidates from those records.
#include <algorithm>
#include <limits>
#include <vector>

#include "models/fhg/block_row.h"
#include "models/fhg/fhg_regs.h"
#include "test_images.h"

namespace surfvp::fhg {
namespace {

struct Frame {
    std::vector<uint32_t> values;
    IntegralView view;
};

Frame frame_of(int width, int height, unsigned seed) {
    const cv::Mat image = test::random_image(width, height, seed);
    Frame f{*IntegralCore(32).image(image.data, image.cols, image.rows, image.step), {}};
    f.view = {f.values.data(), width, height, size_t(width)};
    return f;
}

// Every determinant word of every block row and every candidate, at 4, 2 and 1 bytes a
// determinant (the 2- and 1-byte words from narrower precisions), at odd widths and heights
// and at a row address that is not word-aligned (the 4-byte words are streamed past the cache).
TEST(BlockRow, StoresTheRecordsWordByWordAndMarksWhatTheFinderMarksAtEveryWordSize) {
    for (const unsigned det_bits : {32u, 16u, 8u}) {
        Precision precision;
        precision.det_bits = det_bits;
        precision.det_frac_bits = det_bits == 32 ? 16 : 4;
        const HessianCore core(precision);
        const uint32_t det_bytes = fhg_regs::det_bytes_for(det_bits);
        for (auto [w, h] : {std::pair{131, 97}, std::pair{64, 60}}) {
            const Frame f = frame_of(w, h, unsigned(w + det_bits));
            const int blocks = (w + 1) / 2;
            const size_t row_bytes = fhg_regs::row_bytes(uint32_t(w), det_bytes);
            std::vector<int32_t> records(size_t(blocks) * kDeterminantsPerBlock);
            std::vector<uint8_t> stored(row_bytes + 3), expected(row_bytes);
            // The threshold of about the 200th strongest determinant of a size the finder tests.
            std::vector<int32_t> tested;
            for (int by = 0; by < (h + 1) / 2; ++by) {
                core.block_row(f.view, by, records.data());
                for (int bx = 0; bx < blocks; ++bx) tested.push_back(records[size_t(bx) * kDeterminantsPerBlock + 5]);
            }
            std::nth_element(tested.begin(), tested.end() - 200, tested.end());
            const int32_t threshold = *(tested.end() - 200);
            size_t candidates = 0;
            for (int by = 0; by < (h + 1) / 2; ++by) {
                core.block_row(f.view, by, records.data());
                for (size_t k = 0; k < records.size(); ++k)
                    fhg_regs::store_det(&expected[k * det_bytes], records[k], det_bytes);
                std::vector<Candidate> marked;
                LocalMaxFinder(threshold).block_row(records.data(), blocks, by, marked);
                const std::vector<Candidate> found =
                    block_row(core, f.view, by, threshold, det_bytes, stored.data() + 3);
                ASSERT_TRUE(std::equal(expected.begin(), expected.end(), stored.begin() + 3))
                    << det_bits << " bits, " << w << "x" << h << ", block row " << by;
                ASSERT_EQ(found, marked) << det_bits << " bits, " << w << "x" << h << ", block row " << by;
                candidates += found.size();
            }
            // 8-bit words saturate on this image: nothing is strictly above the strongest.
            if (det_bits > 8) {
                EXPECT_GT(candidates, 20u) << det_bits << " bits, " << w << "x" << h;
            }
        }
    }
}

// The lines give the records' values at every position, and each block's peak is the largest
// of the determinants the finder tests, whichever position holds it.
TEST(BlockRow, LinesHoldTheRecordsAndPeaksTheLargestTestedDeterminant) {
    const Frame f = frame_of(75, 41, 3);
    const HessianCore core(Precision{});
    const size_t blocks = (75 + 1) / 2;
    std::vector<int32_t> records(blocks * kDeterminantsPerBlock), peaks(blocks);
    std::vector<bool> held(kDeterminantsPerBlock);
    for (int by = 0; by < (41 + 1) / 2; ++by) {
        core.block_row(f.view, by, records.data());
        const HessianCore::Lines lines = core.block_row_lines(f.view, by, peaks.data());
        ASSERT_EQ(size_t(lines.blocks), blocks);
        for (int bx = 0; bx < lines.blocks; ++bx) {
            const int32_t* record = &records[size_t(bx) * kDeterminantsPerBlock];
            int32_t peak = std::numeric_limits<int32_t>::min();
            int at = -1;
            for (int k = 0; k < kDeterminantsPerBlock; ++k) {
                ASSERT_EQ(lines.at(bx, k), record[k]) << "block " << bx << "," << by << " k " << k;
                if (tested_by_finder(k) && record[k] > peak) peak = record[k], at = k;
            }
            ASSERT_EQ(peaks[size_t(bx)], peak) << "block " << bx << "," << by;
            held[size_t(at)] = true;
        }
    }
    for (int k = 0; k < kDeterminantsPerBlock; ++k)  // every tested position, and only those, held a peak
        EXPECT_EQ(held[size_t(k)], tested_by_finder(k)) << k;
}

}  // namespace
}  // namespace surfvp::fhg
