#pragma once
// CPU cost model of the software stage: counted work -> PPC440 CPU cycles. Plain C++.
//
// Not an ISS and not cycle-accurate: the software runs natively and says what it did, in
// operations of the algorithm (a Haar wavelet, a Gaussian-weighted sample, a 3x3 solve: see
// surf_op_counts.h). Each kind of operation has a cost in CPU cycles from CostParams; the
// integral-image and determinant reads also go, with their bus addresses, through a model of
// the L1 data cache, and each line fill costs `miss_cycles`. Every constant is a named field
// with its source in README.md; the CPU clock is not one of them (the platform turns cycles
// into time).
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <utility>
#include <vector>

#include "sw/cpu_cost/cache_model.h"

namespace surfvp::sw {

enum class Op : uint8_t {
    integral_read,     // 32-bit load from the integral image in DDR (through the cache model)
    determinant_read,  // 32-bit load from the determinant buffer in DDR (through the cache model)
    int_op,            // integer ALU operation: add, compare, shift, address arithmetic
    branch,            // branch, loop iteration
    fload,             // FPU load of the CPU's own data (tables, accumulators, spills)
    fstore,            // FPU store
    fadd,              // add or subtract
    fmul,
    fmadd,             // fused multiply-add (counted 0 so far: ISO C++ builds do not contract)
    fdiv,
    fsqrt,
    fcmp,
    fmove,             // fabs, fneg, fmr
    fcvt,              // int <-> float conversion (no direct instruction on 32-bit PowerPC)
    gaussian_weight,   // one sample's Gaussian weight: a table load, or exp() (CostParams)
    exp,               // libm calls, costed as the operations they execute (CostParams)
    atan2,
    sin_cos,           // one sin() or one cos()
    count_
};
constexpr size_t kOpKinds = static_cast<size_t>(Op::count_);
const char* op_name(Op op);

// How many operations of each kind one step of the algorithm performs.
struct OpCounts {
    std::array<uint32_t, kOpKinds> n{};

    constexpr OpCounts() = default;
    constexpr OpCounts(std::initializer_list<std::pair<Op, uint32_t>> counts) {
        for (const auto& c : counts) n[static_cast<size_t>(c.first)] += c.second;
    }
    constexpr uint32_t operator[](Op op) const { return n[static_cast<size_t>(op)]; }
};

// Every constant of the model (README.md has the table with sources). Cycles are CPU cycles
// unless a name says FPU cycles.
struct CostParams {
    // Integer pipeline.
    double int_op_cycles = 1;  // [A] single-issue equivalent of the dual-issue PPC440
    double branch_cycles = 2;  // [A] 1 + share of mispredictions
    double load_cycles = 1;    // [S] a load that hits L1: single-cycle throughput (PPC440 datasheet)
    double miss_cycles = 60;   // [D/A] one 32-byte line fill from DDR; the platform passes its own

    // FPU (APU FPU of the Virtex-5; Virtex-4 APU FPU latencies as proxy, PLATFORM_FACTS §2).
    double fpu_clock_ratio = 2;           // [S] CPU cycles per FPU cycle (DS693: 2:1 and 3:1)
    double fpu_issue_cycles = 4;          // [S, proxy] CPU cycles between two FPU instructions
    double fpu_dependent_fraction = 0.5;  // [A] share of an op's latency beyond issue not hidden
    double fadd_latency = 6;              // FPU cycles [A, proxy]
    double fmul_latency = 5;
    double fmadd_latency = 10;
    double fdiv_latency = 17;  // div and sqrt block the FPU for their whole latency [A]
    double fsqrt_latency = 17;
    double fcmp_latency = 3;
    double fmove_latency = 2;
    double fload_latency = 3;   // FPU cycles, L1 hit
    double fstore_latency = 4;
    double fcvt_cycles = 20;  // [D] int<->float via a store/load through the stack + one FPU op

    // libm calls, as the operations they execute (basic kinds only) plus the call itself.
    double call_cycles = 8;  // [A] branch-and-link, return, prologue/epilogue
    OpCounts exp_ops{{Op::fmul, 10}, {Op::fadd, 8}, {Op::fcvt, 2}, {Op::fcmp, 2},
                     {Op::int_op, 4}, {Op::branch, 2}, {Op::fload, 1}, {Op::fstore, 1}};
    OpCounts atan2_ops{{Op::fdiv, 1}, {Op::fmul, 10}, {Op::fadd, 11}, {Op::fcmp, 6},
                       {Op::fmove, 2}, {Op::int_op, 6}, {Op::branch, 6}, {Op::fload, 2}};
    OpCounts sin_cos_ops{{Op::fmul, 11}, {Op::fadd, 9}, {Op::fcvt, 2}, {Op::fcmp, 2},
                         {Op::int_op, 4}, {Op::branch, 2}, {Op::fload, 1}};
    // sw/surf reads the Gaussian weights of orientation (109) and descriptor (400) samples
    // from tables built once; false charges an exp() per sample instead (OpenSURF's way).
    bool gaussian_from_table = true;

    CacheParams cache;
};

// One line of a report: a kind of work, how often it happened, what it cost.
struct CostLine {
    const char* name;
    uint64_t count;
    double cycles;
};

struct CostBreakdown {
    std::vector<CostLine> lines;  // every Op kind in enum order, then "cache_miss"
    double total_cycles = 0;      // sum of the lines
    uint64_t cache_accesses = 0, cache_hits = 0, cache_misses = 0;
    double hit_rate = 0;
};

class CostCounter {
public:
    // Throws std::invalid_argument for a negative constant, a library call whose operations
    // are not basic kinds, or an invalid cache geometry.
    explicit CostCounter(const CostParams& params);

    void add(Op op, uint64_t n = 1) { counts_[static_cast<size_t>(op)] += n; }
    void add(const OpCounts& ops, uint64_t times = 1);
    // A read of `bytes` at bus `address`: one `kind` (integral_read or determinant_read),
    // and the lines it touches go through the cache model.
    void load(Op kind, uint32_t address, unsigned bytes) {
        add(kind);
        if (!log_misses_) {
            cache_.access(address, bytes);
            return;
        }
        const size_t before = missed_.size();
        cache_.access(address, bytes, &missed_);
        if (missed_.size() > before) stamp_misses(before);
    }

    // With a log, every line fill is also recorded with the exact cycles counted when it was
    // needed, so that a platform can time the fills itself (then give miss_cycles = 0).
    struct Miss {
        uint32_t line;  // bus address of the line
        double cycle;   // exact_cycles() when it missed
    };
    void log_misses(bool on) { log_misses_ = on; }
    const std::vector<Miss>& misses() const { return misses_; }
    void clear_misses() { misses_.clear(); }

    uint64_t count(Op op) const { return counts_[static_cast<size_t>(op)]; }
    double unit_cycles(Op op) const { return unit_[static_cast<size_t>(op)]; }  // per operation
    double exact_cycles() const;  // sum of count x unit + misses x miss_cycles
    uint64_t cycles() const;      // exact_cycles() rounded to the nearest cycle
    // Cycles accumulated since the last take (the driver consume()s them); the takes add up
    // to cycles() exactly.
    uint64_t take_cycles();

    CostBreakdown breakdown() const;
    void reset();  // counts, cache contents and cache counters, takes

    CacheModel& cache() { return cache_; }
    const CacheModel& cache() const { return cache_; }
    const CostParams& params() const { return params_; }

private:
    double mix_cycles(const OpCounts& ops) const;  // basic kinds only
    void stamp_misses(size_t from);

    CostParams params_;
    CacheModel cache_;
    std::array<double, kOpKinds> unit_{};
    std::array<uint64_t, kOpKinds> counts_{};
    uint64_t taken_ = 0;
    bool log_misses_ = false;
    std::vector<uint32_t> missed_;  // lines of the current load that missed
    std::vector<Miss> misses_;
};

}  // namespace surfvp::sw
