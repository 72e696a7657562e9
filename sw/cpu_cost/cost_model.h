#pragma once
// CPU cost model of the software stage: units of work -> PPC440 CPU cycles. Plain C++.
//
// Not an ISS: the software runs natively and tells the counter, per step, how many units of
// work it did (work_units.h: a candidate checked, a determinant compared, a descriptor...).
// Each unit costs the cycles the calibration measured on the same code compiled for the
// PPC440 and run under an instruction-set simulator (calibration.h: its instruction stream
// priced by the PPC440 pipeline model, ppc440_pipeline.h). The DDR reads of the integral image
// and of the determinant buffer also go, with their bus addresses, through the L1 model: a
// line fill costs `miss_cycles`, or, with the log on, is timed by the platform on the memory
// path. The CPU clock is not a parameter here (the platform turns cycles into time).
#include <array>
#include <cstdint>
#include <vector>

#include "sw/cpu_cost/cache_model.h"
#include "sw/cpu_cost/work_units.h"

namespace surfvp::sw {

struct CostParams {
    std::array<double, kUnits> unit_cycles{};  // CPU cycles per unit (calibration.h: unit_prices)
    double miss_cycles = 60;  // [D/A] one 32-byte line fill from DDR; the platform passes 0 and times the fills
    // Integral-image reads the code issues together before it uses any (a burst: their fills
    // overlap on the platform): [A] from sw/surf/haar.h, a rounded Haar sample loads its 8
    // corners at once, an exact one uses each corner's 4 reads right away. Determinant reads
    // are compared as they come (1).
    unsigned reads_per_burst = 1;
    CacheParams cache;
};

// One line of a report: a kind of work, how often it happened, what it cost.
struct CostLine {
    const char* name;
    uint64_t count;
    double cycles;
};

struct CostBreakdown {
    std::vector<CostLine> lines;  // every unit in enum order, then "cache_miss"
    double total_cycles = 0;      // sum of the lines
    uint64_t cache_accesses = 0, cache_hits = 0, cache_misses = 0;
    double hit_rate = 0;
};

// What a counter has accumulated, as a value: a report can be made from one taken at any
// point (the platform's describer keeps the one after the last candidate it handed over).
struct CostTotals {
    std::array<uint64_t, kUnits> units{};
    std::array<double, kSteps> steps{};  // cycles per step: its units and the fills charged while it ran
    uint64_t cache_hits = 0, cache_misses = 0;
};

class CostCounter {
public:
    // Throws std::invalid_argument for a negative or non-finite price or an invalid cache geometry.
    explicit CostCounter(const CostParams& params);

    // The stage's meter (sw/stage/software_stage.h).
    void enter(Step s) {
        close_step();
        step_ = s;
    }
    void leave() { close_step(); }
    void count(Unit u, uint64_t n = 1);
    void load(Read kind, uint32_t address, unsigned bytes) {
        ++reads_[static_cast<size_t>(kind)];
        if (kind == Read::determinant || step_integral_reads_++ % params_.reads_per_burst == 0)
            burst_start_ = step_reads_;
        ++step_reads_;
        const size_t before = missed_.size();
        const CacheModel::Result r = cache_.access(address, bytes, log_misses_ ? &missed_ : nullptr);
        if (r.misses) charge_misses(r.misses, before);
    }
    void begin_frame() { cache_.invalidate(); }  // DMA rewrote the buffers: the L1 is not coherent

    // With a log, every line fill is also recorded with the cycle it was needed at, so that a
    // platform can time the fills itself (then give miss_cycles = 0). A step's price is charged
    // whole, so when the step ends its fills are spread over its cycles in the order of its
    // reads: a fill needed by the step's k-th of n reads is stamped k/n of the way through, k
    // being the first read of its burst (CostParams::reads_per_burst), so a burst's fills share
    // one stamp.
    struct Miss {
        uint32_t line;  // bus address of the line
        double cycle;   // when it was needed (exact cycles)
    };
    void log_misses(bool on) { log_misses_ = on; }
    bool logs_misses() const { return log_misses_; }
    const std::vector<Miss>& misses() const { return misses_; }
    void clear_misses();

    uint64_t counted(Unit u) const { return units_[static_cast<size_t>(u)]; }
    uint64_t reads(Read kind) const { return reads_[static_cast<size_t>(kind)]; }
    double unit_cycles(Unit u) const { return params_.unit_cycles[static_cast<size_t>(u)]; }
    double exact_cycles() const { return cycles_; }  // units x prices + misses x miss_cycles
    uint64_t cycles() const;                         // exact_cycles() rounded to the nearest cycle
    // Cycles accumulated since the last take (the driver consume()s them); the takes add up
    // to cycles() exactly.
    uint64_t take_cycles();
    // Where the cycles went: each step's units and the fills charged while it ran.
    const std::array<double, kSteps>& step_cycles() const { return steps_; }

    CostTotals totals() const { return {units_, steps_, cache_.hits(), cache_.misses()}; }
    CostBreakdown breakdown(const CostTotals& totals) const;
    CostBreakdown breakdown() const { return breakdown(totals()); }
    void reset();  // counts, cache contents and cache counters, takes

    CacheModel& cache() { return cache_; }
    const CacheModel& cache() const { return cache_; }
    const CostParams& params() const { return params_; }

private:
    void charge_misses(uint32_t misses, size_t logged_from);
    void close_step();  // spreads the step's logged fills over its cycles

    CostParams params_;
    CacheModel cache_;
    std::array<uint64_t, kUnits> units_{};
    std::array<uint64_t, 2> reads_{};
    std::array<double, kSteps> steps_{};
    double cycles_ = 0;
    uint64_t taken_ = 0;
    Step step_ = Step::check;
    bool log_misses_ = false;
    std::vector<uint32_t> missed_;  // lines of the current load that missed
    std::vector<Miss> misses_;
    std::vector<uint64_t> miss_read_;  // for the current step's misses: which of its reads
    double step_start_ = 0;            // cycles when the current step began
    uint64_t step_reads_ = 0;
    uint64_t step_integral_reads_ = 0;
    uint64_t burst_start_ = 0;  // the step's read that began the current burst
    size_t step_first_miss_ = 0;
};

}  // namespace surfvp::sw
