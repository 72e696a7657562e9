#pragma once
// Timing of a PPC440 instruction stream: an in-order, dual-issue scoreboard with the APU FPU
// beside it. `surfvp calibrate` runs the software stage's real instruction stream (the stage
// compiled for the PPC440 and executed by qemu-ppc) through it; the cycles it gives per unit of
// work become the native cost model's prices (calibration.h). Plain C++.
//
// What it models: two issue slots per cycle, one instruction per pipe per cycle (i: complex
// integer, compare, branch, SPR moves; j: simple integer; l: loads and stores; f: the APU FPU),
// a source operand waits for its producer's latency, each class of APU instruction holds the
// APU's issue for its own occupancy (an FP load 10 cycles, a store 4, arithmetic 2: xfpu.md),
// FP loads wait for the ones still outstanding (one, the Virtex-4 APU FPU sheet), divides and
// square roots share one unpipelined unit, the FPU's latencies are the configured precision's
// column, conditional branches are predicted by a 2-bit counter per branch, and a taken branch
// the BTAC does not hold costs a bubble. What it does not: cache misses (every access hits; the L1 model and the
// platform's memory path add the fills), the instruction cache, TLB misses, interrupts.
// README.md lists each parameter with its source.
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace surfvp::sw {

enum class InsnClass : uint8_t {
    integer,   // add, logical, shift, rotate, move, load immediate
    multiply,  // mullw, mulli, mulhw(u)
    divide,    // divw(u)
    compare,   // cmpw(i), cmplw(i), record forms' CR0
    cr_logical,
    spr_move,  // mflr, mtlr, mfctr, mtctr, mfcr, mtcrf, mfxer
    load,      // integer loads
    store,     // integer stores
    branch,
    fadd,  // fadd(s), fsub(s)
    fmul,
    fmadd,  // fmadd(s), fmsub(s), fnmadd(s), fnmsub(s)
    fdiv,
    fsqrt,
    fcmp,
    fmove,     // fmr, fabs, fneg, fnabs
    fconvert,  // fctiw(z), frsp
    fload,
    fstore,
    fstatus,  // mffs, mtfsf, mtfsb0/1
    system,   // sc, sync, isync, and anything not classed above
};
constexpr size_t kInsnClasses = 21;
const char* insn_class_name(InsnClass c);
bool is_fpu_arithmetic(InsnClass c);  // runs on the APU FPU (not its loads and stores)

// Register numbers: 0-31 GPRs, 32-63 FPRs, 64-71 CR fields, then LR, CTR, XER, FPSCR.
enum : uint8_t { kFpr = 32, kCr = 64, kLr = 72, kCtr = 73, kXer = 74, kFpscr = 75, kRegisters = 76 };

// One instruction as the pipeline sees it, decoded once from its disassembly.
struct Insn {
    InsnClass cls = InsnClass::system;
    uint8_t ndst = 0, nsrc = 0;
    uint8_t dst[3] = {};
    uint8_t src[4] = {};
    uint8_t repeat = 1;            // lmw / stmw: one access per register
    bool conditional = false;      // a conditional branch (predicted)
    bool btac = false;             // a branch the BTAC predicts: unconditional or bdnz
    bool backward = false;         // a conditional branch to a lower address (statically predicted taken)
    bool round_to_single = false;  // frsp: a double-precision FPU's rounding, which code for the single one has none of
};

// Decodes qemu's disassembly of one instruction ("lwzu r13, -0x480(r8)"); unknown mnemonics
// are InsnClass::system with no operands (the trace tool lists them).
Insn decode(const std::string& mnemonic, const std::string& operands);

// FPU cycles of each operation in one precision: GCC's xfpu.md (the Xilinx APU FPU), its
// single- and double-precision columns.
struct FpuColumn {
    double fadd, fmul, fmadd, fdiv, fsqrt, fcmp, fmove, fconvert, fload, fstore;
};
FpuColumn fpu_column(bool double_precision);

struct PipelineParams {
    double issue_width = 2;        // [S] PPC440 core datasheet: dual issue
    double load_latency = 3;       // [S] GCC's PPC440 description (rs6000/440.md): load 3
    double multiply_latency = 3;   // [S] 440.md: imul 3
    double divide_latency = 34;    // [S] 440.md: idiv 34, the i pipe busy 33
    double compare_latency = 2;    // [S] 440.md: compare 2
    double spr_latency = 4;        // [S] 440.md: mtjmpr 4 (move to LR/CTR)
    double mfspr_latency = 2;      // [S] 440.md: mfjmpr 2 (move from LR/CTR)
    double taken_bubble = 1;       // [S] PPC440 datasheet: the BTAC "avoids a one cycle penalty"
    double mispredict_cycles = 4;  // [A] not retrieved: a 7-stage pipeline resolving in EX
    double fpu_ratio = 2;          // [S] DS693: CPU cycles per FPU cycle (2:1 or 3:1)
    double double_precision = 0;   // fpu.precision: 0 single, 1 double (the column below, frsp)
    // CPU cycles each class of APU instruction holds the APU's issue (no other FPU instruction
    // issues meanwhile): xfpu.md's reservations (Xfpu_issue*2, *10, *4).
    double apu_issue = 2;  // arithmetic: add, multiply, multiply-add
    double apu_load_issue = 10, apu_store_issue = 4, apu_move_issue = 2, apu_compare_issue = 2, apu_convert_issue = 2,
           apu_divide_issue = 2;
    double apu_outstanding_loads = 1;  // [S] Virtex-4 APU FPU sheet: one outstanding FP load
    double apu_overhead = 2;           // [S/proxy] xfpu.md: 2 CPU cycles for register file access and write back
    // FPU cycles, the precision's column (xfpu.md; fpu_column()).
    double fadd = 5, fmul = 4, fmadd = 10, fdiv = 27, fsqrt = 27, fcmp = 1, fmove = 1, fconvert = 4, fload = 4,
           fstore = 1;
    double fpu_overlap = 1;  // [S] DS693: integer work issues while the FPU computes; 0: the CPU waits for each result

    // The defaults with the FPU of this precision (its latency column).
    static PipelineParams for_precision(bool double_precision);
};

// A knob of the pipeline: a scenario parameter, its field, and the two values the
// calibration also prices the stream at (for the native model's sensitivity and, when
// `band`, the verdict's assumption band).
struct PipelineKnob {
    const char* key;  // scenario parameter ("ppc.load_latency")
    double PipelineParams::*field;
    double low, high;
    bool band;
    const char* unit;  // cycles, fpu_cycles, count, switch (off/on), precision (single/double)
    const char* help;
    const char* source;
    const char* why;  // the band's reason (or why the probe points)
};
const std::vector<PipelineKnob>& pipeline_knobs();
// A choice knob's value as the scenario writes it ("on", "double"); nullptr for a number.
const char* knob_choice(const PipelineKnob& k, double value);

class Ppc440Pipeline {
public:
    explicit Ppc440Pipeline(const PipelineParams& params);  // throws std::invalid_argument

    // Issues one executed instruction; `pc` identifies the branch for its predictor, `taken`
    // says where a branch went. Returns the cycle it issued in.
    uint64_t issue(const Insn& insn, uint32_t pc, bool taken);
    uint64_t cycles() const;  // when the last issued instruction's results are all available
    uint64_t issue_cycle() const { return cycle_; }
    void reset();

private:
    enum Pipe { kPipeI, kPipeJ, kPipeL, kPipeF, kPipes };
    double result_latency(InsnClass c) const;
    double occupancy(InsnClass c) const;  // CPU cycles the instruction holds the APU's issue
    Pipe pick_pipe(InsnClass c, uint64_t at) const;
    bool used(Pipe p, uint64_t at) const { return pipe_used_[p] == at + 1; }

    PipelineParams p_;
    uint64_t cycle_ = 0;               // the current issue cycle
    unsigned issued_now_ = 0;          // instructions issued in cycle_
    uint64_t pipe_used_[kPipes] = {};  // cycle + 1 when the pipe was used last
    uint64_t ready_[kRegisters] = {};  // when each register's value is available
    uint64_t fpu_free_ = 0;            // when the APU takes its next instruction
    uint64_t divider_free_ = 0;        // when the unpipelined divide / square-root unit takes the next
    std::vector<uint64_t> loads_;      // when each outstanding FP load's data is in (oldest first)
    uint64_t i_pipe_free_ = 0;         // after a divide
    uint64_t next_ = 0;                // no instruction issues before this (after a branch, or a waited-for FPU result)
    uint64_t last_ = 0;                // latest result
    std::unordered_map<uint32_t, uint8_t> bht_;  // 2-bit counters per branch address
};

}  // namespace surfvp::sw
