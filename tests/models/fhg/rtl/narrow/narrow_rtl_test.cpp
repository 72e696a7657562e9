// The verilated datapath on another machine, at a precision whose paths the defaults never
// reach: 20-bit accumulators that wrap, 12-bit responses (9 fraction bits: |r| < 4) and 18-bit
// determinants (16 fraction bits: |det| < 2) that saturate, read by six pair buses from a
// `banked` line FIFO (two BRAMs a line, columns interleaved, two ports each at the FHG clock),
// each bus reaching the lines of one of two groups (fhg.line_groups = 2).
// Every determinant of real crops must still be HessianCore's at that precision, bit for bit,
// each block in the schedule's interval; the test counts the saturations it compared. (Its own
// Verilator build, tests/CMakeLists.txt, is given the fields narrow() and machine() set.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "../co_simulation.h"
#include "models/fhg/sequence_cache.h"

namespace surfvp::fhg {
namespace {

Precision narrow() {
    Precision p;
    p.accumulator_bits = 20;
    p.response_bits = 12;
    p.det_bits = 18;
    return p;
}

SequenceParams machine() {
    SequenceParams s;
    s.line_fifo = LineFifo::banked;
    s.bus_word = BusWord::pair;
    s.read_buses = 6;
    s.line_groups = 2;  // each lane reaches half of the lines, which the default build (every line) does not wire
    return s;
}

// Responses beyond 12 bits and determinants beyond 18 in the crop, as HessianCore forms them.
struct Saturations {
    uint64_t responses = 0, determinants = 0;
};
Saturations saturations(const Crop& crop, const Precision& p) {
    const HessianCore core(p);
    const int64_t response_max = (int64_t(1) << (p.response_bits - 1)) - 1,
                  det_max = (int64_t(1) << (p.det_bits - 1)) - 1;
    Saturations s;
    for (int by = 0; by < crop.view.height / 2; ++by)
        for (int bx = 0; bx < crop.view.width / 2; ++bx)
            for (int k = 0; k < kDeterminantsPerBlock; ++k) {
                const BlockDeterminant d = block_determinant(k);
                const int x = 2 * bx + d.px, y = 2 * by + d.py;
                if (!HessianCore::inside(crop.view.width, crop.view.height, x, y, d.size)) continue;
                const HessianCore::Sums sums = core.sums(crop.view, x, y, d.size);
                for (int64_t sum : {sums.xx, sums.yy, sums.xy})
                    s.responses += std::llabs(sum * core.reciprocal(d.size) >> p.recip_shift) > response_max;
                const int32_t det = core.determinant(crop.view, x, y, d.size);
                s.determinants += det == det_max || det == -det_max - 1;
            }
    return s;
}

TEST(FhgRtlNarrow, SaturatedResponsesAndDeterminantsMatchTheModelBitForBit) {
    const cv::Mat graf = test::real_image("graf1.png"), castle = castle_frame();
    ASSERT_FALSE(graf.empty() || castle.empty());
    const Precision p = narrow();
    for (const auto& [name, image] : {std::pair{"graf1", graf}, std::pair{"castle", castle}}) {
        const Crop crop = crop_of(image);
        const SequenceParams sequence = machine();
        const Sequence schedule = cached_sequence(sequence);
        const CoSimulation r = co_simulate(crop, encode_sequence(schedule, sequence), sequence, p);
        EXPECT_EQ(r.determinants, 128u * 96u * 18u) << name;
        EXPECT_EQ(r.mismatches, 0u) << name << ": " << r.first_mismatch;
        ASSERT_FALSE(r.block_cycles.empty());
        const auto [low, high] = std::minmax_element(r.block_cycles.begin(), r.block_cycles.end());
        EXPECT_EQ(*low, uint64_t(schedule.interval)) << name;
        EXPECT_EQ(*high, uint64_t(schedule.interval)) << name;
        const Saturations s = saturations(crop, p);
        EXPECT_GT(s.responses, 1000u) << name;  // the saturation paths were compared, not only reachable
        EXPECT_GT(s.determinants, 100u) << name;
        std::printf(
            "%s at 20/12/18 bits, banked, 6 pair buses: %llu determinants, %llu mismatches, %d cycles a block; %llu "
            "responses and %llu determinants saturated\n",
            name, (unsigned long long)r.determinants, (unsigned long long)r.mismatches, schedule.interval,
            (unsigned long long)s.responses, (unsigned long long)s.determinants);
    }
}

}  // namespace
}  // namespace surfvp::fhg
