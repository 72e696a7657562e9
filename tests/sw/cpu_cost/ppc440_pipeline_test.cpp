// The PPC440 pipeline model: cycles of small instruction sequences against the rules of
// ppc440_pipeline.h, worked out by hand; and the decoder on qemu's disassembly.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sw/cpu_cost/ppc440_pipeline.h"

namespace surfvp::sw {
namespace {

// Issues a straight-line sequence ("mnemonic|operands") and returns the cycles to its last result.
uint64_t run(const std::vector<std::string>& code, const PipelineParams& p = {}) {
    Ppc440Pipeline pipe(p);
    uint32_t pc = 0x1000;
    for (const std::string& line : code) {
        const size_t bar = line.find('|');
        pipe.issue(decode(line.substr(0, bar), bar == std::string::npos ? "" : line.substr(bar + 1)), pc, false);
        pc += 4;
    }
    return pipe.cycles();
}

TEST(Ppc440Decode, ReadsOperandsAsQemuPrintsThem) {
    const Insn load = decode("lwzu", " r13, -0x480(r8)");
    EXPECT_EQ(load.cls, InsnClass::load);
    ASSERT_EQ(load.ndst, 2);  // the value and the updated base
    EXPECT_EQ(load.dst[0], 13);
    EXPECT_EQ(load.dst[1], 8);
    ASSERT_EQ(load.nsrc, 1);
    EXPECT_EQ(load.src[0], 8);
    const Insn store = decode("stfs", "f1, 8(r1)");
    EXPECT_EQ(store.cls, InsnClass::fstore);
    EXPECT_EQ(store.ndst, 0);
    EXPECT_EQ(store.nsrc, 2);
    const Insn cmp = decode("cmpwi", "cr7, r9, 0");
    EXPECT_EQ(cmp.cls, InsnClass::compare);
    EXPECT_EQ(cmp.dst[0], kCr + 7);
    const Insn branch = decode("bne", "cr7, 0x10000480");
    EXPECT_TRUE(branch.conditional);
    EXPECT_EQ(branch.src[0], kCr + 7);
    EXPECT_EQ(decode("fmadds", "f0, f1, f2, f3").cls, InsnClass::fmadd);
    EXPECT_EQ(decode("fctiwz", "f0, f1").cls, InsnClass::fconvert);
    EXPECT_EQ(decode("mullw", "r3, r4, r5").cls, InsnClass::multiply);
    EXPECT_EQ(decode("mtctr", "r9").dst[0], kCtr);
    EXPECT_TRUE(decode("bdnz", "0x100").btac);
    EXPECT_EQ(decode("bl", "0x10003000").dst[0], kLr);
    EXPECT_EQ(decode("stmw", "r29, 8(r1)").repeat, 3);
}

TEST(Ppc440Pipeline, TwoIndependentIntegerOpsPerCycle) {
    // 4 independent adds: cycles 0, 0, 1, 1; the last result at 2.
    EXPECT_EQ(run({"add|r3, r4, r5", "add|r6, r7, r8", "add|r9, r10, r11", "add|r12, r13, r14"}), 2u);
    PipelineParams single;
    single.issue_width = 1;
    EXPECT_EQ(run({"add|r3, r4, r5", "add|r6, r7, r8", "add|r9, r10, r11", "add|r12, r13, r14"}, single), 4u);
}

TEST(Ppc440Pipeline, ALoadFeedsItsUserAfterTheLoadLatency) {
    // lwz at 0, result at 3; the dependent add issues at 3, its result at 4.
    EXPECT_EQ(run({"lwz|r3, 0(r1)", "add|r4, r3, r3"}), 4u);
    PipelineParams slow;
    slow.load_latency = 5;
    EXPECT_EQ(run({"lwz|r3, 0(r1)", "add|r4, r3, r3"}, slow), 6u);
    // Two loads share the one load/store pipe: cycles 0 and 1.
    EXPECT_EQ(run({"lwz|r3, 0(r1)", "lwz|r4, 4(r1)"}), 4u);
}

TEST(Ppc440Pipeline, ApuLatencyAndIssueRate) {
    // A dependent fadds chain: each waits issue 2 + 5 x 2 + overhead 2 = 14 cycles.
    EXPECT_EQ(run({"fadds|f1, f2, f3", "fadds|f4, f1, f1"}), 28u);
    // Independent fadds go one per apu_issue (2) cycles: issued at 0, 2, 4; the last done at 18.
    EXPECT_EQ(run({"fadds|f1, f2, f3", "fadds|f4, f5, f6", "fadds|f7, f8, f9"}), 18u);
    PipelineParams ratio3;
    ratio3.fpu_ratio = 3;
    EXPECT_EQ(run({"fadds|f1, f2, f3", "fadds|f4, f1, f1"}, ratio3), 38u);  // 2 + 15 + 2, twice
}

TEST(Ppc440Pipeline, DividesShareOneUnpipelinedUnitAndOverlapCanBeOff) {
    // fdivs at 0 done at 2 + 27 x 2 + 2 = 58; an independent fadds issues once the divide has
    // left the issue (2): done 2 + 14; the last result is the divide's.
    EXPECT_EQ(run({"fdivs|f1, f2, f3", "fadds|f4, f5, f6"}), 58u);
    // A second divide waits for the unit: 58 + 58.
    EXPECT_EQ(run({"fdivs|f1, f2, f3", "fdivs|f4, f5, f6"}), 116u);
    // Integer work after an FPU op: overlapped it issues at once, else it waits for the result.
    EXPECT_EQ(run({"fadds|f1, f2, f3", "add|r3, r4, r5"}), 14u);
    PipelineParams serial;
    serial.fpu_overlap = 0;
    EXPECT_EQ(run({"fadds|f1, f2, f3", "add|r3, r4, r5"}, serial), 15u);
}

TEST(Ppc440Pipeline, LoadsAndStoresHoldTheApuIssue) {
    // An FP load holds the issue 10 cycles (xfpu.md) and is the one outstanding load: the
    // second issues at 10, its data at 10 + 2 + 4 x 2 = 20.
    EXPECT_EQ(run({"lfs|f1, 0(r1)", "lfs|f2, 4(r1)"}), 20u);
    // Freed after 2 cycles, the second still waits for the first's data (one outstanding) ...
    PipelineParams quick;
    quick.apu_load_issue = 2;
    EXPECT_EQ(run({"lfs|f1, 0(r1)", "lfs|f2, 4(r1)"}, quick), 20u);
    // ... unless two may be outstanding: issued at 2, data at 12.
    quick.apu_outstanding_loads = 2;
    EXPECT_EQ(run({"lfs|f1, 0(r1)", "lfs|f2, 4(r1)"}, quick), 12u);
    // A store holds the issue 4 cycles: the next add issues at 4, done at 4 + 14.
    EXPECT_EQ(run({"stfs|f1, 0(r1)", "fadds|f2, f3, f4"}), 18u);
    // Integer loads do not wait for the APU.
    EXPECT_EQ(run({"lfs|f1, 0(r1)", "lwz|r3, 4(r1)"}), 10u);
}

TEST(Ppc440Pipeline, PrecisionSelectsTheColumnAndFrsp) {
    // Single: frsp is not there (code for the single FPU has nothing to round); the fadds waits
    // only for the fsub: 14 + 14.
    const std::vector<std::string> code = {"fsub|f1, f2, f3", "frsp|f4, f1", "fadds|f5, f4, f4"};
    EXPECT_EQ(run(code), 28u);
    // Double: fsub 2 + 7 x 2 + 2 = 18, frsp 2 + 6 x 2 + 2 = 16, fadds 18 again.
    EXPECT_EQ(run(code, PipelineParams::for_precision(true)), 52u);
    EXPECT_TRUE(decode("frsp", "f4, f1").round_to_single);
    EXPECT_EQ(fpu_column(true).fmadd, 19);
    EXPECT_EQ(fpu_column(false).fload, 4);
}

TEST(Ppc440Pipeline, MispredictedBranchesCostThePenalty) {
    // A forward conditional branch starts weakly predicted not taken: taken, it is
    // mispredicted and the next instruction issues 1 + 4 cycles later; the counter then says
    // taken, and a correctly predicted taken branch the BTAC does not hold costs 1 bubble.
    Ppc440Pipeline pipe{PipelineParams{}};
    const Insn bne = decode("bne", "cr7, 0x2000");
    const Insn add = decode("add", "r3, r4, r5");
    uint64_t t = pipe.issue(bne, 0x1000, true);
    EXPECT_EQ(pipe.issue(add, 0x2000, false), t + 5);
    t = pipe.issue(bne, 0x1000, true);
    EXPECT_EQ(pipe.issue(add, 0x2000, false), t + 2);
    t = pipe.issue(bne, 0x1000, false);  // predicted taken, not taken: mispredicted
    EXPECT_EQ(pipe.issue(add, 0x1004, false), t + 5);
}

TEST(Ppc440Pipeline, KnobsAreTheParametersFields) {
    for (bool dp : {false, true})
        for (const PipelineKnob& k : pipeline_knobs()) {
            EXPECT_LE(k.low, PipelineParams::for_precision(dp).*k.field) << k.key;
            EXPECT_GE(k.high, PipelineParams::for_precision(dp).*k.field) << k.key;
            EXPECT_LT(k.low, k.high) << k.key;
        }
    PipelineParams bad;
    bad.load_latency = -1;
    EXPECT_THROW(Ppc440Pipeline{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace surfvp::sw
