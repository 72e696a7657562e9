#include "sw/cpu_cost/cost_model.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace surfvp::sw {
namespace {

constexpr const char* kNames[kOpKinds] = {
    "integral_read", "determinant_read", "int_op", "branch", "fload", "fstore", "fadd", "fmul", "fmadd",
    "fdiv",          "fsqrt",            "fcmp",   "fmove",  "fcvt",  "gaussian_weight", "exp", "atan2", "sin_cos"};

void check(bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("cpu cost: " + what);
}

bool basic(Op op) {
    return op != Op::integral_read && op != Op::determinant_read && op != Op::gaussian_weight && op != Op::exp &&
           op != Op::atan2 && op != Op::sin_cos;
}

void check_params(const CostParams& p) {
    const double values[] = {p.int_op_cycles,  p.branch_cycles,  p.load_cycles,    p.miss_cycles,
                             p.fpu_clock_ratio, p.fpu_issue_cycles, p.fadd_latency, p.fmul_latency,
                             p.fmadd_latency,  p.fdiv_latency,   p.fsqrt_latency,  p.fcmp_latency,
                             p.fmove_latency,  p.fload_latency,  p.fstore_latency, p.fcvt_cycles,
                             p.call_cycles};
    for (double v : values) check(std::isfinite(v) && v >= 0, "every cycle count and latency must be >= 0");
    check(p.fpu_dependent_fraction >= 0 && p.fpu_dependent_fraction <= 1, "fpu_dependent_fraction must be 0..1");
    for (const OpCounts* mix : {&p.exp_ops, &p.atan2_ops, &p.sin_cos_ops})
        for (size_t k = 0; k < kOpKinds; ++k)
            check(!mix->n[k] || basic(static_cast<Op>(k)),
                  std::string("a library call may only count basic operations, not ") + kNames[k]);
}

// A pipelined FPU instruction: it occupies the issue slot, and the part of its latency
// beyond that is exposed for the share of operations that wait for their operand.
double pipelined(const CostParams& p, double latency_fpu_cycles) {
    const double latency = latency_fpu_cycles * p.fpu_clock_ratio;
    const double exposed = latency > p.fpu_issue_cycles ? latency - p.fpu_issue_cycles : 0.0;
    return p.fpu_issue_cycles + p.fpu_dependent_fraction * exposed;
}

}  // namespace

const char* op_name(Op op) { return static_cast<size_t>(op) < kOpKinds ? kNames[static_cast<size_t>(op)] : "?"; }

CostCounter::CostCounter(const CostParams& params) : params_(params), cache_(params.cache) {
    check_params(params_);
    const CostParams& p = params_;
    auto set = [&](Op op, double cycles) { unit_[static_cast<size_t>(op)] = cycles; };
    set(Op::integral_read, p.load_cycles);
    set(Op::determinant_read, p.load_cycles);
    set(Op::int_op, p.int_op_cycles);
    set(Op::branch, p.branch_cycles);
    set(Op::fload, pipelined(p, p.fload_latency));
    set(Op::fstore, pipelined(p, p.fstore_latency));
    set(Op::fadd, pipelined(p, p.fadd_latency));
    set(Op::fmul, pipelined(p, p.fmul_latency));
    set(Op::fmadd, pipelined(p, p.fmadd_latency));
    set(Op::fdiv, p.fdiv_latency * p.fpu_clock_ratio);
    set(Op::fsqrt, p.fsqrt_latency * p.fpu_clock_ratio);
    set(Op::fcmp, pipelined(p, p.fcmp_latency));
    set(Op::fmove, pipelined(p, p.fmove_latency));
    set(Op::fcvt, p.fcvt_cycles);
    // Library calls last: they are priced from the basic kinds above.
    set(Op::exp, p.call_cycles + mix_cycles(p.exp_ops));
    set(Op::atan2, p.call_cycles + mix_cycles(p.atan2_ops));
    set(Op::sin_cos, p.call_cycles + mix_cycles(p.sin_cos_ops));
    // The exponent -(u^2 + v^2) / (2 sigma^2) with 1 / (2 sigma^2) hoisted: 3 fmul + 1 fadd.
    const double computed = unit_[size_t(Op::exp)] + 3 * unit_[size_t(Op::fmul)] + unit_[size_t(Op::fadd)];
    set(Op::gaussian_weight, p.gaussian_from_table ? unit_[size_t(Op::fload)] : computed);
}

double CostCounter::mix_cycles(const OpCounts& ops) const {
    double cycles = 0;
    for (size_t k = 0; k < kOpKinds; ++k) cycles += double(ops.n[k]) * unit_[k];
    return cycles;
}

void CostCounter::add(const OpCounts& ops, uint64_t times) {
    for (size_t k = 0; k < kOpKinds; ++k) counts_[k] += uint64_t(ops.n[k]) * times;
}

void CostCounter::stamp_misses(size_t from) {
    const double now = exact_cycles();
    for (size_t i = from; i < missed_.size(); ++i) misses_.push_back({missed_[i], now});
    missed_.clear();
}

double CostCounter::exact_cycles() const {
    double cycles = double(cache_.misses()) * params_.miss_cycles;
    for (size_t k = 0; k < kOpKinds; ++k) cycles += double(counts_[k]) * unit_[k];
    return cycles;
}

uint64_t CostCounter::cycles() const { return uint64_t(std::llround(exact_cycles())); }

uint64_t CostCounter::take_cycles() {
    const uint64_t now = cycles();
    const uint64_t taken = now - taken_;
    taken_ = now;
    return taken;
}

CostBreakdown CostCounter::breakdown() const {
    CostBreakdown b;
    for (size_t k = 0; k < kOpKinds; ++k) {
        b.lines.push_back({kNames[k], counts_[k], double(counts_[k]) * unit_[k]});
        b.total_cycles += b.lines.back().cycles;
    }
    b.lines.push_back({"cache_miss", cache_.misses(), double(cache_.misses()) * params_.miss_cycles});
    b.total_cycles += b.lines.back().cycles;
    b.cache_accesses = cache_.accesses();
    b.cache_hits = cache_.hits();
    b.cache_misses = cache_.misses();
    b.hit_rate = cache_.hit_rate();
    return b;
}

void CostCounter::reset() {
    counts_.fill(0);
    misses_.clear();
    cache_.invalidate();
    cache_.reset_counters();
    taken_ = 0;
}

}  // namespace surfvp::sw
