// CostCounter: counts -> cycles by the formula of sw/cpu_cost/README.md, exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "sw/cpu_cost/cost_model.h"
#include "sw/cpu_cost/surf_op_counts.h"

namespace surfvp::sw {
namespace {

// Defaults: issue 4 CPU cycles, ratio 2, half the latency beyond issue exposed.
//   fadd 4 + (12 - 4) / 2 = 8, fmul 4 + (10 - 4) / 2 = 7, fcmp 4 + (6 - 4) / 2 = 5,
//   fmove 4 (latency 4 = issue), fload 5, fstore 6, fmadd 12, fdiv = fsqrt = 34 (blocking).
TEST(CostCounter, DefaultUnitCosts) {
    const CostCounter c{CostParams{}};
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fadd), 8);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fmul), 7);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fcmp), 5);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fmove), 4);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fload), 5);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fstore), 6);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fmadd), 12);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fdiv), 34);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fsqrt), 34);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fcvt), 20);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::int_op), 1);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::branch), 2);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::integral_read), 1);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::determinant_read), 1);
    // exp: call 8 + 10 fmul 70 + 8 fadd 64 + 2 fcvt 40 + 2 fcmp 10 + 4 int + 2 branch 4 + fload 5 + fstore 6
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::exp), 211);
    // atan2: 8 + fdiv 34 + 10 fmul 70 + 11 fadd 88 + 6 fcmp 30 + 2 fmove 8 + 6 int + 6 branch 12 + 2 fload 10
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::atan2), 266);
    // sin or cos: 8 + 11 fmul 77 + 9 fadd 72 + 2 fcvt 40 + 2 fcmp 10 + 4 int + 2 branch 4 + fload 5
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::sin_cos), 220);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::gaussian_weight), 5);  // a table load
}

TEST(CostCounter, ComputedGaussianWeightIsAnExpAndItsExponent) {
    CostParams p;
    p.gaussian_from_table = false;
    EXPECT_DOUBLE_EQ(CostCounter(p).unit_cycles(Op::gaussian_weight), 211 + 3 * 7 + 8);
}

TEST(CostCounter, CountsToCyclesByHand) {
    CostCounter c{CostParams{}};
    c.add(Op::fadd, 3);
    c.add(Op::fmul, 2);
    c.add(Op::fdiv);
    c.add(Op::int_op, 10);
    c.add(Op::branch, 4);
    for (uint32_t a : {0u, 4u, 8u, 32u, 36u}) c.load(Op::integral_read, 0x1000 + a, 4);  // 2 lines
    EXPECT_EQ(c.count(Op::integral_read), 5u);
    EXPECT_EQ(c.cache().misses(), 2u);
    // 3 x 8 + 2 x 7 + 34 + 10 x 1 + 4 x 2 + 5 reads x 1 + 2 misses x 60
    EXPECT_EQ(c.cycles(), 24u + 14 + 34 + 10 + 8 + 5 + 120);
}

TEST(CostCounter, FormulaFollowsTheParameters) {
    CostParams p;
    p.fpu_clock_ratio = 3;
    p.fpu_issue_cycles = 3;
    p.fpu_dependent_fraction = 1;  // every op waits for its operand: full latency
    p.miss_cycles = 100;
    p.load_cycles = 2;
    CostCounter c(p);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fadd), 18);  // 6 FPU cycles x 3
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fmul), 15);
    EXPECT_DOUBLE_EQ(c.unit_cycles(Op::fmove), 6);
    p.fpu_dependent_fraction = 0;  // fully overlapped: the issue interval alone
    EXPECT_DOUBLE_EQ(CostCounter(p).unit_cycles(Op::fadd), 3);
    c.load(Op::determinant_read, 0, 4);
    EXPECT_EQ(c.cycles(), 2u + 100);
}

TEST(CostCounter, OpCountsMixesAddTimesTheirCounts) {
    CostCounter c{CostParams{}};
    const OpCounts mix{{Op::fadd, 2}, {Op::fmul, 1}, {Op::int_op, 3}};
    c.add(mix, 10);
    EXPECT_EQ(c.count(Op::fadd), 20u);
    EXPECT_EQ(c.count(Op::fmul), 10u);
    EXPECT_EQ(c.count(Op::int_op), 30u);
    EXPECT_EQ(c.cycles(), 10u * (2 * 8 + 7 + 3));
}

TEST(CostCounter, TakesAddUpToTheRoundedTotal) {
    CostParams p;
    p.fpu_dependent_fraction = 0.25;  // fmul 4 + 1.5 = 5.5: fractional cycles
    CostCounter c(p);
    c.add(Op::fmul);
    EXPECT_EQ(c.take_cycles(), 6u);  // 5.5 rounds to 6
    c.add(Op::fmul);
    EXPECT_EQ(c.take_cycles(), 5u);  // 11 in all
    c.add(Op::fmul, 3);
    EXPECT_DOUBLE_EQ(c.exact_cycles(), 27.5);
    EXPECT_EQ(c.take_cycles(), 17u);  // 28 in all
    EXPECT_EQ(c.take_cycles(), 0u);
    EXPECT_EQ(c.cycles(), 28u);
}

TEST(CostCounter, BreakdownListsEveryKindAndSumsToTheTotal) {
    CostCounter c{CostParams{}};
    c.add(surf_ops::kHaarWavelet, 3);
    c.add(Op::atan2);
    c.load(Op::integral_read, 0, 4);
    c.load(Op::integral_read, 4, 4);
    const CostBreakdown b = c.breakdown();
    ASSERT_EQ(b.lines.size(), kOpKinds + 1);
    double sum = 0;
    for (size_t k = 0; k < kOpKinds; ++k) {
        EXPECT_STREQ(b.lines[k].name, op_name(static_cast<Op>(k)));
        EXPECT_EQ(b.lines[k].count, c.count(static_cast<Op>(k)));
        sum += b.lines[k].cycles;
    }
    EXPECT_STREQ(b.lines.back().name, "cache_miss");
    EXPECT_EQ(b.lines.back().count, 1u);
    sum += b.lines.back().cycles;
    EXPECT_DOUBLE_EQ(b.total_cycles, sum);
    EXPECT_DOUBLE_EQ(b.total_cycles, c.exact_cycles());
    EXPECT_EQ(b.cache_hits, 1u);
    EXPECT_DOUBLE_EQ(b.hit_rate, 0.5);
}

TEST(CostCounter, ResetStartsOver) {
    CostCounter c{CostParams{}};
    c.load(Op::integral_read, 0, 4);
    c.take_cycles();
    c.reset();
    EXPECT_EQ(c.cycles(), 0u);
    c.load(Op::integral_read, 0, 4);  // the line was dropped: a miss again
    EXPECT_EQ(c.cache().misses(), 1u);
    EXPECT_EQ(c.take_cycles(), 61u);
}

TEST(CostCounter, RefusesMeaninglessParameters) {
    CostParams p;
    p.miss_cycles = -1;
    EXPECT_THROW(CostCounter{p}, std::invalid_argument);
    p = CostParams{};
    p.fpu_dependent_fraction = 1.5;
    EXPECT_THROW(CostCounter{p}, std::invalid_argument);
    p = CostParams{};
    p.exp_ops = OpCounts{{Op::atan2, 1}};  // a library call priced by another one
    EXPECT_THROW(CostCounter{p}, std::invalid_argument);
    p = CostParams{};
    p.cache.ways = 3;
    EXPECT_THROW(CostCounter{p}, std::invalid_argument);
}

}  // namespace
}  // namespace surfvp::sw
