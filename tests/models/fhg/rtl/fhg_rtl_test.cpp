// The Verilog reference of the FHG's datapath (models/fhg/rtl), verilated, against the model:
// real integral-image crops stream through the line FIFO, the sequence memory's image, the
// TripleMACs and
// HessianCalc; every determinant must be HessianCore's bit for bit and every block must take
// the schedule's interval. The testbench is the PixelBus: it streams the integral lines in.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>

#include "models/fhg/hessian_core.h"
#include "models/fhg/rtl/rtl_datapath.h"
#include "models/fhg/sequence_cache.h"
#include "models/fhg/sequence_memory.h"
#include "co_simulation.h"
#include "fhg/bus_swap.h"
#include "test_images.h"

namespace surfvp::fhg {
namespace {

// Both schedules on a graf1 and a Castle-simu crop: 128 x 96 blocks each, every determinant
// equal and every block the schedule's interval.
TEST(FhgRtl, DeterminantsAndCyclesMatchTheModelOnRealCrops) {
    const cv::Mat graf = test::real_image("graf1.png"), castle = castle_frame();
    ASSERT_FALSE(graf.empty() || castle.empty());
    for (const auto& [name, image] : {std::pair{"graf1", graf}, std::pair{"castle", castle}}) {
        const Crop crop = crop_of(image);
        for (Scheduler scheduler : {Scheduler::basic, Scheduler::improved}) {
            SequenceParams p;
            p.scheduler = scheduler;
            const Sequence& s = cached_sequence(p);
            const CoSimulation r = co_simulate(crop, encode_sequence(s, p), p);
            const std::string what = std::string(name) + " " + scheduler_name(scheduler);
            EXPECT_EQ(r.blocks, 128u * 96u) << what;
            EXPECT_EQ(r.determinants, 128u * 96u * 18u) << what;
            EXPECT_EQ(r.mismatches, 0u) << what << ": " << r.first_mismatch;
            EXPECT_GT(r.nonzero, r.determinants / 2) << what;  // a comparison of real values, not of zeros
            EXPECT_FALSE(r.overrun) << what;
            ASSERT_FALSE(r.block_cycles.empty());
            const auto [low, high] = std::minmax_element(r.block_cycles.begin(), r.block_cycles.end());
            EXPECT_EQ(*low, uint64_t(s.interval)) << what;
            EXPECT_EQ(*high, uint64_t(s.interval)) << what;
            std::printf("%s: %llu blocks, %llu determinants, %llu mismatches, %llu cycles a block (schedule %d)\n",
                        what.c_str(), (unsigned long long)r.blocks, (unsigned long long)r.determinants,
                        (unsigned long long)r.mismatches, (unsigned long long)*low, s.interval);
        }
    }
}

// One coefficient's sign flipped in the image: the co-simulation names the first block and
// determinant that differ, with both values.
TEST(FhgRtl, ABrokenSequenceImageIsCaughtNamingTheBlockAndTheValue) {
    const cv::Mat graf = test::real_image("graf1.png");
    ASSERT_FALSE(graf.empty());
    const SequenceParams p;
    SequenceImage image = encode_sequence(cached_sequence(p), p);
    const MemoryField& coefficient = image.layout.field("mac5_coefficient");
    size_t c = 0;
    while (!field_value(image.words[c], image.layout.field("mac5_take"))) ++c;
    set_field(image.words[c], coefficient, field_value(image.words[c], coefficient) ^ 1);
    const CoSimulation r = co_simulate(crop_of(graf), image, p, Precision{}, true);
    EXPECT_GT(r.mismatches, 0u);
    EXPECT_EQ(r.first_mismatch.rfind("block (", 0), 0u) << r.first_mismatch;
    EXPECT_NE(r.first_mismatch.find(") determinant 5: RTL "), std::string::npos) << r.first_mismatch;
    EXPECT_NE(r.first_mismatch.find(", HessianCore "), std::string::npos) << r.first_mismatch;
    std::printf("the broken image: %s\n", r.first_mismatch.c_str());
}

// The line FIFO reads each value through the port its lane is wired to: with buses 1 and 2
// traded in one word, every TripleMAC still takes the value it needs, but two lanes ask one
// port for two addresses, and a determinant comes out wrong.
TEST(FhgRtl, TheLineFifoReadsThroughThePortsItsLanesAreWiredTo) {
    const cv::Mat graf = test::real_image("graf1.png");
    ASSERT_FALSE(graf.empty());
    const SequenceParams p;
    SequenceImage image = encode_sequence(cached_sequence(p), p);
    const size_t c = word_a_swap_breaks(image, p, 1, 2);
    ASSERT_LT(c, image.words.size());
    swap_buses(image, c, 1, 2);
    EXPECT_THROW(decode_sequence(image, p), std::invalid_argument);  // what --check would say
    const CoSimulation r = co_simulate(crop_of(graf), image, p, Precision{}, true);
    EXPECT_GT(r.mismatches, 0u) << "the RTL routed the reads freely";
    std::printf("buses 1 and 2 traded in word %zu: %s\n", c, r.first_mismatch.c_str());
}

// fhg.model=rtl's interface: block rows in order, each given once its lines have arrived (a
// row's window and no more), with HessianCore's records and the schedule's cycles, the
// improved script too.
TEST(FhgRtl, BlockRowsFromTheLinesReceivedAreTheCoresWithTheSchedulesCycles) {
    const cv::Mat graf = test::real_image("graf1.png");
    ASSERT_FALSE(graf.empty());
    const Crop crop = test::integral_of(graf(cv::Rect(300, 200, 96, 70)).clone());
    const HessianCore core{Precision{}};
    for (Scheduler scheduler : {Scheduler::basic, Scheduler::improved}) {
        SequenceParams p;
        p.scheduler = scheduler;
        const Sequence& s = cached_sequence(p);
        RtlDatapath rtl(Precision{}, p, 1024, encode_sequence(s, p));
        for (int frame = 0; frame < 2; ++frame) {  // a second frame starts clean
            rtl.start(crop.view.width, crop.view.height);
            for (int by = 0; by < 35; ++by) {
                const int received = std::min(70, 2 * by + kReachAfter + 1);
                const Datapath::Row row = rtl.row(crop.view, received, by);
                ASSERT_EQ(row.records.size(), 48u * 18u);
                std::vector<int32_t> expected(48 * 18);
                core.block_row(crop.view, by, expected.data());
                ASSERT_EQ(row.records, expected) << scheduler_name(scheduler) << " block row " << by;
                ASSERT_EQ(row.cycles, 48u * uint64_t(s.interval)) << scheduler_name(scheduler) << " block row " << by;
            }
        }
    }
}

// Lines withheld: the datapath cannot finish the row and says so instead of hanging.
TEST(FhgRtl, ARowWithoutItsLinesIsAnErrorNotAHang) {
    const Crop crop = test::integral_of(cv::Mat(64, 64, CV_8U, cv::Scalar(90)));
    const SequenceParams p;
    RtlDatapath rtl(Precision{}, p, 1024, encode_sequence(cached_sequence(p), p));
    rtl.start(64, 64);
    try {
        rtl.row(crop.view, 20, 0);  // row 0 needs 26 lines
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("gave 0 of block row 0's 576 determinants and stopped (lines received: "
                                             "20)"),
                  std::string::npos)
            << e.what();
    }
}

// The build verilates the defaults: another configuration is named by the first parameter
// that differs, and the datapath refuses it.
TEST(FhgRtl, AConfigurationTheBuildDidNotVerilateIsNamed) {
    const SequenceParams p;
    EXPECT_EQ(rtl_build_difference(Precision{}, p, 1024), "");
    Precision narrow;
    narrow.response_bits = 16;
    EXPECT_EQ(rtl_build_difference(narrow, p, 1024), "RESPONSE_BITS = 16 here, 18 in the build");
    SequenceParams two_buses;
    two_buses.read_buses = 2;
    EXPECT_NE(rtl_build_difference(Precision{}, two_buses, 1024), "");
    EXPECT_EQ(rtl_build_difference(Precision{}, p, 640), "LINE_WORDS = 640 here, 1024 in the build");
    try {
        RtlDatapath(narrow, p, 1024, encode_sequence(cached_sequence(p), p));
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("RESPONSE_BITS = 16 here, 18 in the build"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace surfvp::fhg
