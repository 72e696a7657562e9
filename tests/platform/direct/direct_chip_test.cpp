// Direct mode's chip programmed as the driver does, without the driver: a frame's integral
// image and determinants are in memory as soon as its integral image streams to the FHG, and
// memory the software reads or writes in the meantime holds the same bytes with and without
// the second thread (which computes them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "models/common/byte_order.h"
#include "models/fhg/fhg_regs.h"
#include "models/iig/iig_regs.h"
#include "models/iig/integral_core.h"
#include "models/intc/intc_regs.h"
#include "platform/address_map.h"
#include "platform/direct/direct_chip.h"

namespace surfvp {
namespace {

constexpr uint32_t kWidth = 64, kHeight = 48;
constexpr uint32_t kImage = 0x10000, kIntegral = 0x20000, kDets = 0x40000, kSecondIntegral = 0x80000;
constexpr uint32_t kRowBytes = fhg_regs::row_bytes(kWidth, 4);
constexpr uint32_t kDetBytes = uint32_t(fhg_regs::buffer_bytes(kWidth, kHeight, 4));

// The frame's pixels (fixed pseudo-random).
std::vector<uint8_t> pixels() {
    std::vector<uint8_t> image(size_t(kWidth) * kHeight);
    uint32_t seed = 11;
    for (uint8_t& p : image) p = uint8_t((seed = seed * 1103515245u + 12345u) >> 24);
    return image;
}

// `integral` (big-endian words) is the integral image of pixels(), as IntegralCore makes it.
void expect_integral_of_pixels(const std::vector<uint8_t>& integral) {
    const std::vector<uint8_t> image = pixels();
    const auto expected = IntegralCore(28).image(image.data(), kWidth, kHeight, kWidth);
    ASSERT_TRUE(expected.has_value());
    ASSERT_EQ(integral.size(), 4 * expected->size());
    for (size_t k = 0; k < expected->size(); ++k) ASSERT_EQ(load_be32(&integral[4 * k]), (*expected)[k]) << k;
}

struct Seen {
    std::vector<uint8_t> integral;  // the integral image, read right after the IIG's START
    std::vector<uint8_t> at_start;  // the determinant buffer right after the IIG's START
    std::vector<uint8_t> at_end;    // and once the FHG is done
    std::vector<uint8_t> second;    // a second integral image, not streamed, once the FHG is done
    uint32_t fhg_status = 0;
};

// One frame: the FHG listening, the IIG streaming to it; the software reads the whole
// determinant buffer and writes 16 bytes into block row 5 before it waits for the FHG. With
// `second_image`, the IIG is started again at once, not streamed, into kSecondIntegral (the
// stream's rows are still being computed), and nothing is read before the FHG is done.
Seen frame(bool parallel, bool second_image = false) {
    Config config;
    config.set("run.parallel", parallel ? "on" : "off", "test");
    config.set("memory.size", "4 MiB", "test");
    DirectChip chip(config, 1);
    const std::vector<uint8_t> image = pixels();
    chip.write(kImage, image.data(), image.size());

    const uint32_t fhg = map::fhg_base(0), iig = map::iig_base(0), intc = map::intc.base;
    chip.write32(intc + intc::IER, 1u << map::irq::fhg(0));
    chip.write32(intc + intc::MER, intc::MER_ME | intc::MER_HIE);
    chip.write32(fhg + fhg_regs::DET_ADDR, kDets);
    chip.write32(fhg + fhg_regs::WIDTH, kWidth);
    chip.write32(fhg + fhg_regs::HEIGHT, kHeight);
    chip.write32(fhg + fhg_regs::THRESHOLD, 0x7fffffff);  // no candidates: the FIFO stays out of it
    chip.write32(fhg + fhg_regs::CTRL, fhg_regs::CTRL_START | fhg_regs::CTRL_IRQ_EN_DONE);
    chip.write32(iig + iig::SRC, kImage);
    chip.write32(iig + iig::DST, kIntegral);
    chip.write32(iig + iig::WIDTH, kWidth);
    chip.write32(iig + iig::HEIGHT, kHeight);
    chip.write32(iig + iig::SRC_STRIDE, kWidth);
    chip.write32(iig + iig::DST_STRIDE, 4 * kWidth);
    chip.write32(iig + iig::CTRL, iig::CTRL_START | iig::CTRL_STREAM);

    Seen seen;
    if (second_image) {
        chip.write32(iig + iig::DST, kSecondIntegral);
        chip.write32(iig + iig::CTRL, iig::CTRL_START);
        chip.wait_for_irq();
        seen.fhg_status = chip.read32(fhg + fhg_regs::STATUS);
        seen.at_end.resize(kDetBytes);
        chip.read(kDets, seen.at_end.data(), kDetBytes);
        seen.second.resize(size_t(kWidth) * kHeight * 4);
        chip.read(kSecondIntegral, seen.second.data(), seen.second.size());
        return seen;
    }
    seen.integral.resize(size_t(kWidth) * kHeight * 4);
    chip.read(kIntegral, seen.integral.data(), seen.integral.size());
    seen.at_start.resize(kDetBytes);
    chip.read(kDets, seen.at_start.data(), kDetBytes);
    const std::vector<uint8_t> marker(16, 0xA5);
    chip.write(kDets + 5 * kRowBytes, marker.data(), marker.size());
    chip.wait_for_irq();
    seen.fhg_status = chip.read32(fhg + fhg_regs::STATUS);
    seen.at_end.resize(kDetBytes);
    chip.read(kDets, seen.at_end.data(), kDetBytes);
    return seen;
}

TEST(DirectChip, AFramesDeterminantsAreInMemoryOnceItStreamsAndTheSoftwaresWritesComeAfterThemOnEitherThread) {
    const Seen serial = frame(false), parallel = frame(true);
    EXPECT_TRUE(serial.fhg_status & fhg_regs::STATUS_DONE);
    EXPECT_FALSE(serial.fhg_status & fhg_regs::STATUS_ERROR);
    // Every block row is there before the FHG has reported one: the last with determinants
    // too, block row 21 (pixel rows 42 and 43; size 9 leaves 4 rows of border).
    const auto row_21 = serial.at_start.begin() + 21 * kRowBytes;
    EXPECT_LT(std::count(row_21, row_21 + kRowBytes, 0), kRowBytes);  // the buffer was zero before
    // The software's bytes stay: they were written after the row they land in.
    EXPECT_TRUE(std::all_of(serial.at_end.begin() + 5 * kRowBytes, serial.at_end.begin() + 5 * kRowBytes + 16,
                            [](uint8_t b) { return b == 0xA5; }));
    EXPECT_TRUE(std::equal(serial.at_end.begin(), serial.at_end.begin() + 5 * kRowBytes, serial.at_start.begin()));
    // The integral image is whole as soon as the software reads it, on the second thread too.
    expect_integral_of_pixels(serial.integral);
    EXPECT_EQ(parallel.integral, serial.integral);
    EXPECT_EQ(parallel.at_start, serial.at_start);
    EXPECT_EQ(parallel.at_end, serial.at_end);
    EXPECT_EQ(parallel.fhg_status, serial.fhg_status);
}

// A second image started while the stream's rows are still being computed (found by the
// registers fuzz target: the rows waited for the later image, queued behind them) leaves the
// stream's determinants as they are, and is whole itself, on either thread.
TEST(DirectChip, AnImageStartedWhileAStreamsRowsAreComputedLeavesThem) {
    const Seen serial = frame(false, true), parallel = frame(true, true);
    EXPECT_TRUE(serial.fhg_status & fhg_regs::STATUS_DONE);
    EXPECT_EQ(parallel.fhg_status, serial.fhg_status);
    EXPECT_EQ(parallel.at_end, serial.at_end);
    EXPECT_EQ(parallel.second, serial.second);
    EXPECT_EQ(serial.at_end, frame(false).at_start);  // the stream's determinants, untouched
    expect_integral_of_pixels(parallel.second);
}

// Without time every fill costs an uncontended one, so the software may count its fills instead
// of listing them: three counted cost what three listed do (write-backs cost nothing).
// Fills one at a time cost what counted ones do; a burst of three (asked at one cycle)
// overlaps on the memory path and costs less than three.
TEST(DirectChip, FillsCountedCostWhatFillsListedCost) {
    Config config;
    config.set("memory.size", "4 MiB", "test");
    DirectChip listed(config, 1), counted(config, 1), burst(config, 1);
    EXPECT_TRUE(counted.times_fills());
    const std::vector<sw::LineTransfer> lines{
        {0x1000, 10, false}, {0x1020, 20, false}, {0x2000, 30, true}, {0x1040, 40, false}};
    const uint64_t a = listed.compute(500, lines, 0);
    const uint64_t b = counted.compute(500, {{0x2000, 30, true}}, 3);
    EXPECT_EQ(a, b);
    EXPECT_GT(a, 500u);  // the fills cost something
    EXPECT_EQ(listed.cycles_consumed(), counted.cycles_consumed());
    EXPECT_EQ(counted.compute(500, {}, 0), 500u);
    const uint64_t together = burst.compute(500, {{0x1000, 10, false}, {0x1020, 10, false}, {0x1040, 10, false}}, 0);
    EXPECT_GT(together, 500 + (a - 500) / 3);
    EXPECT_LT(together, a);
    EXPECT_EQ(together - 500, uint64_t(std::llround(uncontended_fills(config).burst_stall(3).to_seconds() * 400e6)));
}

}  // namespace
}  // namespace surfvp
