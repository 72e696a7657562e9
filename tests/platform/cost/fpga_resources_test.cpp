// The FPGA resource estimate (docs/resources.md): block RAMs in the RAMB36's aspect ratios,
// DSP48E tiles for the multipliers, the totals of a configuration against the device.
#include <cmath>
#include <gtest/gtest.h>

#include "platform/cost/fpga_resources.h"
#include "platform/scenario/scenario.h"

namespace surfvp {
namespace {

TEST(FpgaResources, BlockRamsInTheRamb36AspectRatios) {
    EXPECT_EQ(ramb36_for(1024, 32), 1u);  // a line-FIFO line (docs/sources.md#fhg)
    EXPECT_EQ(ramb36_for(1025, 32), 2u);
    EXPECT_EQ(ramb36_for(1024, 36), 1u);
    EXPECT_EQ(ramb36_for(1024, 37), 2u);  // 512 x 72: two deep
    EXPECT_EQ(ramb36_for(2048, 18), 1u);
    EXPECT_EQ(ramb36_for(32768, 1), 1u);
    EXPECT_EQ(ramb36_for(512, 72), 1u);
    EXPECT_EQ(ramb36_for(60, 215), 3u);  // three 72-bit columns
    EXPECT_EQ(ramb36_for(53, 231), 4u);  // four: the default sequence image
    EXPECT_EQ(ramb36_for(0, 32), 0u);
}

TEST(FpgaResources, DspSlicesTileTheProduct) {
    EXPECT_EQ(dsp48e_for(18, 18), 1u);
    EXPECT_EQ(dsp48e_for(25, 18), 1u);
    EXPECT_EQ(dsp48e_for(18, 25), 1u);
    EXPECT_EQ(dsp48e_for(24, 24), 2u);
    EXPECT_EQ(dsp48e_for(32, 32), 4u);
    EXPECT_EQ(dsp48e_for(13, 24), 1u);
}

Config config(const std::vector<std::string>& sets) {
    return load_scenario(std::string(SURFVP_SOURCE_DIR) + "/scenarios/budget_1024x768.yaml", sets);
}

TEST(FpgaResources, TheDefaultChipFitsTheFx70t) {
    const FpgaResources r = fpga_resources(config({}));
    EXPECT_EQ(r.device, "XC5VFX70T");
    ASSERT_EQ(r.blocks.size(), 4u);
    EXPECT_EQ(r.blocks[1].block, "fhg");
    EXPECT_EQ(r.blocks[1].ramb36, 56 + 1 + 4 + 2 * 8);  // line FIFO, maxima FIFO, sequence, row buffers
    // HessianCalc's products as the RTL forms them: the three sums (24 bit) x K_L (20 bit) two
    // slices each, rxx x ryy and rxy^2 (18 x 18) one each, W (13 bit) x rxy^2 (36 bit) two.
    EXPECT_EQ(r.blocks[1].dsp48e, 3 * 2 + 2 * 1 + 2);
    EXPECT_EQ(r.total.ramb36, 85);
    EXPECT_EQ(r.total.dsp48e, 13);  // HessianCalc's 10 and the single-precision FPU's 3
    EXPECT_TRUE(r.fits());
    // The line FIFO's routing: 16 lanes (4 quad buses), each wired to the 28 BRAMs of its line
    // group (fhg.line_groups = 2). Its flip-flops: a bit a lane, 5 bits of BRAM index in the
    // group for each of a quad's two lines on each bus, the write side's 16 + 16 + 6 + 1, and
    // the turn's bit.
    const FhgParts parts = fhg_parts(config({}));
    EXPECT_EQ(parts.line_routing.luts, 10483);  // 16 x 23.4 x 28, to the whole LUT
    EXPECT_EQ(parts.line_routing.ffs, 16 + 4 * 2 * 5 + 39 + 1);
    EXPECT_NEAR(r.total.luts, 32251, 1);  // 72 % of the FX70T's 44,800: under the 85 % margin
}

// The placement margin: a design above fpga.max_utilisation of the LUTs does not fit, though
// the device has them. Every lane reaching every line (the crossbar) is such a design; a
// quarter of the lines a lane is 14 BRAMs and a 2:1 turn of each lane's value and address.
TEST(FpgaResources, ACrossbarLineFifoIsOverThePlacementMargin) {
    const FpgaResources crossbar = fpga_resources(config({"fhg.line_groups=1"}));
    EXPECT_EQ(fhg_parts(config({"fhg.line_groups=1"})).line_routing.luts, 21974);  // 56 x (23.4 x 16 + 18)
    EXPECT_NEAR(crossbar.total.luts, 43742, 1);
    ASSERT_EQ(crossbar.over.size(), 1u);
    EXPECT_EQ(crossbar.over[0],
              "LUT: 43742 of 44800 (98 %), above the 85 % that places and routes (fpga.max_utilisation)");
    EXPECT_TRUE(fpga_resources(config({"fhg.line_groups=1", "fpga.max_utilisation=0.99"})).fits());
    EXPECT_EQ(fhg_parts(config({"fhg.line_groups=4"})).line_routing.luts, std::round(16 * (23.4 * 14 + 180)));
    // The block RAM's margin apart from the logic's.
    const FpgaResources banked =
        fpga_resources(config({"fhg.line_fifo=banked", "fpga.max_utilisation=1", "fpga.max_block_utilisation=0.9"}));
    ASSERT_EQ(banked.over.size(), 1u);
    EXPECT_EQ(banked.over[0],
              "RAMB36: 141 of 148 (95 %), above the 90 % that places and routes (fpga.max_block_utilisation)");
}

TEST(FpgaResources, StructureMovesTheEstimate) {
    const double base = fpga_resources(config({})).total.ramb36;
    EXPECT_EQ(fpga_resources(config({"fhg.fifo_lines=64"})).total.ramb36, base + 8);
    // Two RAMB36 a line for the banked FIFO; one for the others (1K x 32, or 512 x 72 holding 1024 values).
    EXPECT_EQ(fpga_resources(config({"fhg.line_fifo=banked"})).total.ramb36, base + 56);
    EXPECT_EQ(fpga_resources(config({"fhg.line_fifo=tdp"})).total.ramb36, base);
    EXPECT_EQ(fpga_resources(config({"fhg.line_fifo=sdp72", "fhg.bus_word=scalar"})).total.ramb36 -
                  fpga_resources(config({"fhg.bus_word=scalar"})).total.ramb36,
              0);
    // 24 x 24 bit: two slices each for rxx x ryy and rxy^2; W x rxy^2 (48 bit) still two.
    EXPECT_EQ(fpga_resources(config({"fhg.response_bits=24 bit"})).total.dsp48e, 3 * 2 + 2 * 2 + 2 + 3);
    EXPECT_EQ(fpga_resources(config({"fpu.precision=double"})).total.dsp48e, 10 + 13);
    const FpgaResources two = fpga_resources(config({"soc.accelerators=2"}));
    EXPECT_EQ(two.total.ramb36, 2 * 79 + 6);
    EXPECT_FALSE(two.fits());
    ASSERT_EQ(two.over.size(), 3u);
    // A pair (its IIG and FHG with their PLB interfaces) is 23,631 LUTs: two need 2 x 23,631 +
    // 2,620 (the FPU) + 6,000 (the rest).
    EXPECT_EQ(two.over[0], "LUT: 55882 of 44800 (125 %), more than the device has");
    EXPECT_EQ(two.over[1], "FF: 38100 of 44800 (85 %), above the 85 % that places and routes (fpga.max_utilisation)");
    EXPECT_EQ(two.over[2], "RAMB36: 164 of 148 (111 %), more than the device has");
    // An FX100T's block RAMs (228) and a device with 20,000 slices (80,000 LUTs).
    EXPECT_TRUE(fpga_resources(config({"soc.accelerators=2", "fpga.ramb36=228", "fpga.slices=20000"})).fits());
    EXPECT_FALSE(fpga_resources(config({"soc.accelerators=2", "fpga.ramb36=228", "fpga.slices=16000"})).fits())
        << "55,882 of 64,000 LUTs is 87 %";
}

}  // namespace
}  // namespace surfvp
