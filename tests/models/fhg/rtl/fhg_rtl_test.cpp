// The Verilog reference of the FHG's datapath (models/fhg/rtl), verilated, against the model:
// real integral-image crops stream through the line FIFO, the sequence memory's image, the
// TripleMACs and
// HessianCalc; every determinant must be HessianCore's bit for bit and every block must take
// the schedule's interval. The testbench is the PixelBus: it streams the integral lines in.
#include <gtest/gtest.h>

#include <Vfhg_datapath.h>
#include <verilated.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "models/fhg/hessian_core.h"
#include "models/fhg/sequence_cache.h"
#include "models/fhg/sequence_memory.h"
#include "models/host/atomic_file.h"
#include "test_images.h"

namespace surfvp::fhg {
namespace {

using Crop = test::Integral;

// The integral image of a 256 x 192 crop from the middle of an image.
Crop crop_of(const cv::Mat& image) {
    return test::integral_of(image(cv::Rect((image.cols - 256) / 2, (image.rows - 192) / 2, 256, 192)).clone());
}

cv::Mat castle_frame() {
    const std::string path = std::string(VISP_DATA_DIR) + "/mbt-depth/Castle-simu/Images/Image_0001.pgm";
    cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (image.empty()) ADD_FAILURE() << path << " is missing: install the Debian package visp-images-data";
    return image;
}

struct CoSimulation {
    uint64_t blocks = 0, determinants = 0, mismatches = 0, nonzero = 0;
    std::string first_mismatch;
    std::vector<uint64_t> block_cycles;  // between consecutive blocks' first determinants
    bool overrun = false;
};

// Runs the whole crop through the RTL with this sequence image and compares every determinant.
CoSimulation co_simulate(const Crop& crop, const std::string& image_file, const SequenceParams& p,
                         bool stop_at_mismatch = false) {
    const HessianCore core{Precision{}};
    auto context = std::make_unique<VerilatedContext>();
    const std::string plusarg = "+sequence=" + image_file;
    const char* argv[] = {"fhg_rtl_test", plusarg.c_str()};
    context->commandArgs(2, argv);
    Vfhg_datapath rtl(context.get());
    // The PixelBus: the crop's integral values, row by row, one a cycle while the FIFO takes them.
    size_t next = 0;
    const size_t values = size_t(crop.view.width) * size_t(crop.view.height);
    auto tick = [&] {
        rtl.in_valid = next < values;
        rtl.in_value =
            next < values ? crop.view.at(int(next % size_t(crop.view.width)), int(next / size_t(crop.view.width))) : 0;
        rtl.clk = 0;
        rtl.eval();
        const bool taken = rtl.in_valid && rtl.in_ready;  // at this edge
        rtl.clk = 1;
        rtl.eval();
        next += taken;
    };
    rtl.rst = 1;
    tick();
    tick();
    rtl.rst = 0;
    rtl.width = uint16_t(crop.view.width);
    rtl.height = uint16_t(crop.view.height);
    rtl.start = 1;
    tick();
    rtl.start = 0;
    CoSimulation out;
    std::array<int32_t, kDeterminantsPerBlock> expected{};
    const uint64_t total = uint64_t((crop.view.width + 1) / 2) * uint64_t((crop.view.height + 1) / 2);
    uint64_t cycle = 0, last_first = 0;
    for (; out.determinants < total * kDeterminantsPerBlock && cycle < 200 * total + 1000; ++cycle) {
        if (stop_at_mismatch && out.mismatches) break;
        tick();
        if (!rtl.det_valid) continue;
        const int k = rtl.det_index;
        if (k == 0) {
            expected = core.block(crop.view, rtl.det_block_x / 2, rtl.det_block_y / 2);
            if (out.blocks++) out.block_cycles.push_back(cycle - last_first);
            last_first = cycle;
        }
        ++out.determinants;
        out.nonzero += expected[size_t(k)] != 0;
        if (int32_t(rtl.det_value) != expected[size_t(k)] && out.mismatches++ == 0)
            out.first_mismatch = "block (" + std::to_string(rtl.det_block_x / 2) + ", " +
                                 std::to_string(rtl.det_block_y / 2) + ") determinant " + std::to_string(k) + ": RTL " +
                                 std::to_string(int32_t(rtl.det_value)) + ", HessianCore " +
                                 std::to_string(expected[size_t(k)]);
    }
    out.overrun = rtl.overrun;
    rtl.final();
    return out;
}

std::string write_image(const SequenceImage& image, const std::string& name) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("surfvp_rtl_" + std::to_string(::getpid()) + "_" + name + ".mem"))
            .string();
    write_file_atomically(path, to_readmemh(image, name));
    return path;
}

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
            const std::string file = write_image(encode_sequence(s, p), scheduler_name(scheduler));
            const CoSimulation r = co_simulate(crop, file, p);
            std::filesystem::remove(file);
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
    const std::string file = write_image(image, "broken");
    const CoSimulation r = co_simulate(crop_of(graf), file, p, true);
    std::filesystem::remove(file);
    EXPECT_GT(r.mismatches, 0u);
    EXPECT_EQ(r.first_mismatch.rfind("block (", 0), 0u) << r.first_mismatch;
    EXPECT_NE(r.first_mismatch.find(") determinant 5: RTL "), std::string::npos) << r.first_mismatch;
    EXPECT_NE(r.first_mismatch.find(", HessianCore "), std::string::npos) << r.first_mismatch;
    std::printf("the broken image: %s\n", r.first_mismatch.c_str());
}

}  // namespace
}  // namespace surfvp::fhg
