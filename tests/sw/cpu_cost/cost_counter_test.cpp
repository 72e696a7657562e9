// CostCounter: units x their prices + fills x miss_cycles, by step, exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "sw/cpu_cost/cost_model.h"

namespace surfvp::sw {
namespace {

CostParams priced() {
    CostParams p;
    p.unit_cycles = {500, 60, 40, 3000, 800, 170, 120000, 1100, 190000};  // candidate .. descriptor
    p.miss_cycles = 60;
    return p;
}

TEST(CostCounter, UnitsTimesPricesByStep) {
    CostCounter c(priced());
    c.enter(Step::check);
    c.count(Unit::candidate);
    c.count(Unit::scan);
    c.count(Unit::compare, 27);
    c.enter(Step::orientation);
    c.count(Unit::orientation);
    c.count(Unit::angle, 100);
    c.load(Read::integral, 0x1000, 4);  // one fill, charged to the orientation
    EXPECT_DOUBLE_EQ(c.step_cycles()[size_t(Step::check)], 500 + 60 + 27 * 40);
    EXPECT_DOUBLE_EQ(c.step_cycles()[size_t(Step::orientation)], 120000 + 100 * 1100 + 60);
    EXPECT_DOUBLE_EQ(c.exact_cycles(), 500 + 60 + 27 * 40 + 120000 + 100 * 1100 + 60);
    EXPECT_EQ(c.counted(Unit::compare), 27u);
    EXPECT_EQ(c.reads(Read::integral), 1u);
    EXPECT_EQ(c.reads(Read::determinant), 0u);
}

TEST(CostCounter, TakesAddUpToTheRoundedTotal) {
    CostParams p = priced();
    p.unit_cycles[size_t(Unit::compare)] = 0.4;  // fractional prices round only in the takes
    CostCounter c(p);
    uint64_t taken = 0;
    for (int i = 0; i < 7; ++i) {
        c.count(Unit::compare);
        taken += c.take_cycles();
    }
    EXPECT_EQ(taken, c.cycles());
    EXPECT_EQ(c.cycles(), uint64_t(std::llround(7 * 0.4)));
}

TEST(CostCounter, BreakdownListsEveryUnitAndSumsToTheTotal) {
    CostCounter c(priced());
    c.count(Unit::descriptor, 2);
    c.load(Read::determinant, 0x2000, 4);
    c.load(Read::determinant, 0x2004, 4);
    const CostBreakdown b = c.breakdown();
    ASSERT_EQ(b.lines.size(), kUnits + 1);
    EXPECT_STREQ(b.lines[size_t(Unit::descriptor)].name, "descriptor");
    EXPECT_DOUBLE_EQ(b.lines[size_t(Unit::descriptor)].cycles, 2 * 190000);
    EXPECT_STREQ(b.lines.back().name, "cache_miss");
    EXPECT_EQ(b.cache_misses, 1u);
    EXPECT_EQ(b.cache_hits, 1u);
    EXPECT_DOUBLE_EQ(b.total_cycles, 2 * 190000 + 60);
    EXPECT_DOUBLE_EQ(b.total_cycles, c.exact_cycles());
}

TEST(CostCounter, ResetAndANewFrameStartOver) {
    CostCounter c(priced());
    c.load(Read::integral, 0x1000, 4);
    c.begin_frame();  // DMA rewrote the buffers: the line is gone
    c.load(Read::integral, 0x1000, 4);
    EXPECT_EQ(c.cache().misses(), 2u);
    c.reset();
    EXPECT_EQ(c.exact_cycles(), 0);
    EXPECT_EQ(c.cache().misses(), 0u);
    EXPECT_EQ(c.reads(Read::integral), 0u);
}

TEST(CostCounter, RefusesMeaninglessPrices) {
    CostParams p = priced();
    p.unit_cycles[0] = -1;
    EXPECT_THROW(CostCounter{p}, std::invalid_argument);
    p = priced();
    p.miss_cycles = std::nan("");
    EXPECT_THROW(CostCounter{p}, std::invalid_argument);
}

}  // namespace
}  // namespace surfvp::sw
