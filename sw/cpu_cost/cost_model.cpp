#include "sw/cpu_cost/cost_model.h"

#include <cmath>
#include <stdexcept>

namespace surfvp::sw {

const char* step_name(Step s) {
    constexpr const char* kNames[kSteps] = {"check", "interpolation", "laplacian", "orientation", "descriptor"};
    return kNames[static_cast<size_t>(s)];
}

const char* unit_name(Unit u) {
    constexpr const char* kNames[kUnits] = {"candidate", "scan",        "compare", "solve",      "keypoint",
                                            "laplacian", "orientation", "angle",   "descriptor", "msurf"};
    return kNames[static_cast<size_t>(u)];
}

CostCounter::CostCounter(const CostParams& params) : params_(params), cache_(params.cache) {
    for (double c : params_.unit_cycles)
        if (!std::isfinite(c) || c < 0) throw std::invalid_argument("cpu cost: every unit's cycles must be >= 0");
    if (!std::isfinite(params_.miss_cycles) || params_.miss_cycles < 0)
        throw std::invalid_argument("cpu cost: miss_cycles must be >= 0");
    if (params_.reads_per_burst < 1) throw std::invalid_argument("cpu cost: reads_per_burst must be >= 1");
}

void CostCounter::count(Unit u, uint64_t n) {
    const size_t k = static_cast<size_t>(u);
    units_[k] += n;
    const double c = double(n) * params_.unit_cycles[k];
    steps_[static_cast<size_t>(step_of(u))] += c;
    cycles_ += c;
}

void CostCounter::charge_misses(uint32_t misses, size_t logged_from) {
    const double c = double(misses) * params_.miss_cycles;
    steps_[static_cast<size_t>(step_)] += c;
    cycles_ += c;
    if (!log_misses_) return;
    for (size_t i = logged_from; i < missed_.size(); ++i) {
        // Written in place: a Miss built aside and copied in was read back whole right after
        // its two halves were stored, which the store buffer cannot forward (a stall a fill).
        Miss& m = misses_.emplace_back();
        m.line = missed_[i];
        m.cycle = cycles_;
        miss_read_.push_back(burst_start_);
    }
    missed_.clear();
}

void CostCounter::close_step() {
    const double span = cycles_ - step_start_;
    for (size_t i = step_first_miss_; i < misses_.size(); ++i)
        misses_[i].cycle = step_start_ + span * double(miss_read_[i - step_first_miss_]) / double(step_reads_);
    miss_read_.clear();
    step_first_miss_ = misses_.size();
    step_start_ = cycles_;
    step_reads_ = step_integral_reads_ = burst_start_ = 0;
}

uint64_t CostCounter::cycles() const { return uint64_t(std::llround(cycles_)); }

uint64_t CostCounter::take_cycles() {
    const uint64_t now = cycles();
    const uint64_t taken = now - taken_;
    taken_ = now;
    return taken;
}

CostBreakdown CostCounter::breakdown(const CostTotals& t) const {
    CostBreakdown b;
    for (size_t k = 0; k < kUnits; ++k) {
        b.lines.push_back({unit_name(Unit(k)), t.units[k], double(t.units[k]) * params_.unit_cycles[k]});
        b.total_cycles += b.lines.back().cycles;
    }
    b.lines.push_back({"cache_miss", t.cache_misses, double(t.cache_misses) * params_.miss_cycles});
    b.total_cycles += b.lines.back().cycles;
    b.cache_hits = t.cache_hits;
    b.cache_misses = t.cache_misses;
    b.cache_accesses = t.cache_hits + t.cache_misses;
    b.hit_rate = b.cache_accesses ? double(t.cache_hits) / double(b.cache_accesses) : 0.0;
    return b;
}

void CostCounter::clear_misses() {
    misses_.clear();
    miss_read_.clear();
    step_first_miss_ = 0;
}

void CostCounter::reset() {
    clear_misses();
    step_start_ = 0;
    step_reads_ = step_integral_reads_ = burst_start_ = 0;
    units_.fill(0);
    reads_.fill(0);
    steps_.fill(0);
    cycles_ = 0;
    cache_.invalidate();
    cache_.reset_counters();
    taken_ = 0;
}

}  // namespace surfvp::sw
