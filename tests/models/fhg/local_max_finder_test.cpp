// LocalMaxFinder: every true 3x3x3 maximum is marked; what it marks beyond is counted.
#include <cstdio>
#include <random>
#include <set>
#include <tuple>

#include "models/fhg/hessian_core.h"
#include "models/fhg/local_max_finder.h"
#include "test_images.h"

namespace surfvp::fhg {
namespace {

TEST(LocalMaxFinder, PackingRoundTrips) {
    for (const Candidate c :
         {Candidate{0, 0, 1}, Candidate{1023, 767, 4}, Candidate{4095, 4095, 3}, Candidate{17, 9, 2}}) {
        const uint32_t w = pack_candidate(c);
        EXPECT_TRUE(w >> 31) << "valid bit";
        EXPECT_EQ((w >> 27) & 1, uint32_t(c.octave() == 2));
        EXPECT_EQ(unpack_candidate(w), c);
    }
}

// The determinant planes of a frame, from the block records.
struct Planes {
    int width, height;
    std::vector<int32_t> records;  // block rows of block records
    int32_t at(int x, int y, int size_index) const {
        const int bx = x / 2, by = y / 2, blocks = (width + 1) / 2;
        const int32_t* r = &records[(size_t(by) * blocks + bx) * kDeterminantsPerBlock];
        if (size_index <= 3) return r[4 * size_index + 2 * (y % 2) + x % 2];
        return r[16 + size_index - 4];  // 39, 51: even pixels only
    }
};

// A true maximum: strictly above threshold and all 26 neighbours of its octave's grid.
bool true_maximum(const Planes& p, int x, int y, int octave, int s, int32_t threshold) {
    static const int kOctave[2][4] = {{0, 1, 2, 3}, {1, 3, 4, 5}};
    const int step = octave;  // 1 or 2
    const int32_t v = p.at(x, y, kOctave[octave - 1][s]);
    if (v <= threshold) return false;
    for (int ds = -1; ds <= 1; ++ds)
        for (int dy = -step; dy <= step; dy += step)
            for (int dx = -step; dx <= step; dx += step) {
                if (!ds && !dy && !dx) continue;
                if (p.at(x + dx, y + dy, kOctave[octave - 1][s + ds]) >= v) return false;
            }
    return true;
}

// block_row() skips a block when none of the determinants block() tests is above the threshold:
// with each of the 18 record positions alone above it in turn (the rest random below), the row
// marks exactly what block() marks block by block.
TEST(LocalMaxFinder, ARowMarksWhatItsBlocksMarkWhicheverDeterminantIsAboveTheThreshold) {
    const int32_t threshold = 1000;
    const LocalMaxFinder finder(threshold);
    std::mt19937 random(5);
    std::uniform_int_distribution<int32_t> below(-5000, threshold);
    const int blocks = 3 * kDeterminantsPerBlock;
    std::vector<int32_t> records(size_t(blocks) * kDeterminantsPerBlock);
    for (int32_t& r : records) r = below(random);
    for (int bx = 0; bx < blocks; ++bx)  // block bx: position bx % 18 above, a different one each
        records[size_t(bx) * kDeterminantsPerBlock + size_t(bx % kDeterminantsPerBlock)] = threshold + 1 + bx;
    std::vector<Candidate> by_row, by_block;
    finder.block_row(records.data(), blocks, 7, by_row);
    for (int bx = 0; bx < blocks; ++bx) {
        const int32_t* record = records.data() + size_t(bx) * kDeterminantsPerBlock;
        finder.block(record, bx ? record - kDeterminantsPerBlock : nullptr, bx, 7, by_block);
    }
    ASSERT_EQ(by_row.size(), by_block.size());
    EXPECT_GE(by_row.size(), 10u);  // octave 1's 8 tested positions and octave 2's 2, at least once each
    for (size_t i = 0; i < by_row.size(); ++i) EXPECT_EQ(pack_candidate(by_row[i]), pack_candidate(by_block[i])) << i;
}

TEST(LocalMaxFinder, MarksEveryTrueMaximumOnARealImage) {
    const cv::Mat image = test::graf_1024x768();
    ASSERT_FALSE(image.empty());
    const auto values = *IntegralCore(28).image(image.data, image.cols, image.rows, image.step);
    const IntegralView ii{values.data(), image.cols, image.rows, size_t(image.cols)};
    const HessianCore core(Precision{});
    const int blocks = image.cols / 2;
    Planes planes{image.cols, image.rows,
                  std::vector<int32_t>(size_t(blocks) * (image.rows / 2) * kDeterminantsPerBlock)};
    for (int by = 0; by < image.rows / 2; ++by)
        core.block_row(ii, by, &planes.records[size_t(by) * blocks * kDeterminantsPerBlock]);

    for (double threshold : {100.0, 400.0}) {
        const int32_t t = core.from_float(threshold);
        const LocalMaxFinder finder(t);
        std::vector<Candidate> marked;
        for (int by = 0; by < image.rows / 2; ++by)
            finder.block_row(&planes.records[size_t(by) * blocks * kDeterminantsPerBlock], blocks, by, marked);
        std::set<std::tuple<int, int, int>> marks;
        for (const Candidate& c : marked) marks.insert({c.x, c.y, c.size_index});
        int truths = 0;
        for (int octave = 1; octave <= 2; ++octave)
            for (int s = 1; s <= 2; ++s) {
                const int size_index = octave == 1 ? s : (s == 1 ? 3 : 4);
                for (int y = 2; y < image.rows - 2; y += octave)
                    for (int x = 2; x < image.cols - 2; x += octave) {
                        if (!true_maximum(planes, x, y, octave, s, t)) continue;
                        ++truths;
                        ASSERT_TRUE(marks.count({x, y, size_index}))
                            << "true maximum at " << x << "," << y << " size " << kSizes[size_index] << " not marked";
                    }
            }
        std::printf("threshold %g: %d true 3x3x3 maxima, %zu marked (%.1f per true maximum)\n", threshold, truths,
                    marked.size(), double(marked.size()) / std::max(truths, 1));
        EXPECT_GT(truths, 40);
        EXPECT_GE(int(marked.size()), truths);
    }
}

}  // namespace
}  // namespace surfvp::fhg
