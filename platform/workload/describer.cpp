#include "platform/workload/describer.h"

#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <fstream>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <fmt/format.h>
#include <vector>

#include "models/fhg/fhg_regs.h"
#include "models/fhg/local_max_finder.h"
#include "platform/scenario/block_params.h"
#include "platform/workload/cpu_cost_params.h"
#include "platform/workload/workload.h"
#include "models/common/byte_order.h"
#include "models/host/worker.h"
#include "sw/cpu_cost/calibration.h"
#include "sw/cpu_cost/calibration_dump.h"
#include "sw/stage/software_stage.h"

namespace surfvp {

namespace {

double knob_value(const Config& c, const sw::PipelineKnob& k) {
    const std::string unit = k.unit;
    return unit == "switch"      ? (c.choice(k.key) == "on" ? 1.0 : 0.0)
           : unit == "precision" ? (c.choice(k.key) == "double" ? 1.0 : 0.0)
           : unit == "count"     ? double(c.count(k.key))
                                 : double(c.cycles(k.key));
}

}  // namespace

sw::PipelineParams pipeline_params(const Config& c) {
    sw::PipelineParams set;  // every knob as the configuration has it
    for (const sw::PipelineKnob& k : sw::pipeline_knobs()) set.*k.field = knob_value(c, k);
    sw::PipelineParams p = sw::PipelineParams::for_precision(set.double_precision != 0);
    for (const sw::PipelineKnob& k : sw::pipeline_knobs())
        if (std::string(k.unit) != "fpu_cycles" || c.origin(k.key) != "default")  // else the precision's column
            p.*k.field = set.*k.field;
    return p;
}

namespace {

sw::CostParams cost_params(const Config& c, surf::HaarMode haar) {
    sw::CostParams p = sw::calibrated_cost_params(haar, pipeline_params(c));
    p.miss_cycles = 0;  // the platform times each fill on the memory path (Hal::compute)
    p.reads_per_burst = haar == surf::HaarMode::rounded ? 8 : 4;  // sw/surf/haar.h (CostParams)
    p.cache = cache_parameter_table().make(c);
    p.cache.line_bytes = cpu_params(c).line_bytes;
    return p;
}

// `surfvp calibrate`: where the describers made from now on record what the stage saw.
std::string g_record_inputs, g_record_expected;
bool g_calibrating = false;  // calibrating_stage(): units without a price are what it measures

// Each frame's buffers as the CPU saw them and its FIFO words in the driver's order, and what
// the native stage made of each word, in the firmware's formats (calibration_dump.h).
class InputRecorder {
public:
    InputRecorder(const std::string& inputs, const std::string& expected)
        : inputs_(inputs, std::ios::binary | std::ios::app), expected_(expected, std::ios::binary | std::ios::app) {
        if (!inputs_ || !expected_) throw std::runtime_error("calibrate: cannot write " + inputs + " or " + expected);
    }
    ~InputRecorder() { flush(); }

    void frame(const sw::FrameBuffers& b, const sw::StageParams& p) {
        flush();
        namespace dump = sw::calibration_dump;
        const size_t det_bytes = size_t(fhg_regs::buffer_bytes(uint32_t(b.width), uint32_t(b.height), b.det_bytes));
        header_ = {dump::kMagic,
                   uint32_t(b.width),
                   uint32_t(b.height),
                   b.det_frac_bits,
                   b.det_bytes,
                   p.haar == surf::HaarMode::rounded,
                   p.upright,
                   p.descriptor == surf::DescriptorKind::msurf,
                   p.threshold,
                   p.max_offset,
                   b.integral_address,
                   b.determinants_address,
                   uint32_t(b.integral_stride * b.height),
                   uint32_t(det_bytes),
                   0};
        integral_.assign(b.integral, b.integral + header_.integral_bytes);
        determinants_.assign(b.determinants, b.determinants + det_bytes);
    }
    void word(uint32_t w, const std::optional<surf::Keypoint>& kp) {
        uint8_t be[4];
        store_be32(be, w);
        words_.insert(words_.end(), be, be + 4);
        sw::calibration_dump::Result r{};
        if (kp) sw::calibration_dump::fill(r, *kp);
        sw::calibration_dump::swap_words_to_big_endian(r);
        expected_.write(reinterpret_cast<const char*>(&r), sizeof r);
        ++header_.words;
    }

private:
    void flush() {
        if (!header_.words) return;
        sw::calibration_dump::FrameHeader h = header_;
        sw::calibration_dump::swap_words_to_big_endian(h);
        inputs_.write(reinterpret_cast<const char*>(&h), sizeof h);
        inputs_.write(reinterpret_cast<const char*>(integral_.data()), std::streamsize(integral_.size()));
        inputs_.write(reinterpret_cast<const char*>(determinants_.data()), std::streamsize(determinants_.size()));
        inputs_.write(reinterpret_cast<const char*>(words_.data()), std::streamsize(words_.size()));
        header_.words = 0;
        words_.clear();
    }

    std::ofstream inputs_, expected_;
    sw::calibration_dump::FrameHeader header_{};
    std::vector<uint8_t> integral_, determinants_, words_;
};

// libSSA2's phase 4 on the software stage: the frame's buffers read in place (DMI), the
// stage's counted work and its L1 fills handed back for the CPU to spend, and the described
// keypoint's record written back to the task's ring.
//
// With the simulator's second thread lent to it (run.parallel), the stage describes a task's
// candidates ahead, in the worker's idle time (Worker::set_background), one candidate a piece
// and in the driver's order, while the kernel simulates the next task's hardware. It is the
// same stage on the same bytes in the same order (the driver keeps a task's buffers until it
// is reported, and describes its candidates one after the other: Describer::ahead), so each
// result is the one describe() would have made; a candidate not yet done when the driver asks
// for it is done then, on the kernel's thread. The report counts only what the driver was
// handed (a run cut short by run.max_time may have described further ahead).
class StageDescriber : public sw::ssa2::Describer {
public:
    StageDescriber(const sw::StageParams& params, const sw::CostParams& cost, unsigned line_bytes)
        : params_(params), stage_(params, sw::CostCounter(cost)), line_bytes_(line_bytes) {
        if (!g_record_inputs.empty()) recorder_ = std::make_unique<InputRecorder>(g_record_inputs, g_record_expected);
        handed_ = tally();
    }

    // The worker whose idle time describes ahead; nullptr takes it back (nothing of this
    // describer runs on it after the call).
    void share_worker(Worker* worker) {
        if (worker_) worker_->set_background(nullptr);
        worker_ = recorder_ ? nullptr : worker;  // `surfvp calibrate` records each word as it is described
        if (worker_) worker_->set_background([this] { return describe_ahead(); });
    }

    void ahead(sw::Hal& hal, const std::vector<uint32_t>& candidates, const sw::ssa2::FrameInMemory& frame) override {
        if (!worker_) return;
        {
            std::lock_guard<std::mutex> lock(stage_mutex_);
            fills_for(hal);
            start_task(frame);
            ahead_ = Ahead{frame.task, candidates, buffers(hal, frame), std::vector<Result>(candidates.size())};
            described_.store(0, std::memory_order_relaxed);
        }
        worker_->poke();
    }

    std::optional<surf::Keypoint> describe(sw::Hal& hal, uint32_t word, const sw::ssa2::FrameInMemory& frame,
                                           sw::ssa2::Work& work) override {
        Result r = ahead_ && ahead_->task == frame.task ? take_ahead(word) : describe_now(hal, word, frame);
        handed_ = r.tally;
        if (r.error) std::rethrow_exception(r.error);
        work = std::move(r.work);
        if (r.keypoint) write_back_record(frame, work);
        return r.keypoint;
    }

    const sw::SoftwareStage& stage() const { return stage_; }
    // What the stage had counted after the last candidate handed to the driver.
    struct Tally {
        sw::SoftwareStage::Stats stats;
        sw::CostTotals cost;
    };
    const Tally& handed() const { return handed_; }
    bool rounded() const { return params_.haar == surf::HaarMode::rounded; }

private:
    struct Result {
        std::optional<surf::Keypoint> keypoint;
        sw::ssa2::Work work;
        Tally tally;
        std::exception_ptr error;
    };
    // A task described ahead: results[k] is ready once described_ > k.
    struct Ahead {
        int task;
        std::vector<uint32_t> words;
        sw::FrameBuffers buffers;
        std::vector<Result> results;
        size_t handed = 0;     // handed to the driver (its thread only)
        bool stopped = false;  // after a failed check or an error the driver describes no further
    };

    Tally tally() const { return {stage_.stats(), stage_.cost().totals()}; }

    sw::FrameBuffers buffers(sw::Hal& hal, const sw::ssa2::FrameInMemory& frame) const {
        const size_t integral_bytes = size_t(frame.width) * frame.height * 4;
        const size_t det_bytes =
            size_t(fhg_regs::buffer_bytes(uint32_t(frame.width), uint32_t(frame.height), frame.det_bytes));
        return {hal.map(frame.integral, integral_bytes),
                frame.integral,
                size_t(frame.width) * 4,
                hal.map(frame.determinants, det_bytes),
                frame.determinants,
                frame.width,
                frame.height,
                frame.det_frac_bits,
                frame.det_bytes};
    }

    // The stage's misses as the platform takes its fills: each stamped with the cycle that
    // needed it where the platform times them, only counted where it does not (direct mode),
    // which spares a record a miss. Under stage_mutex_.
    void fills_for(const sw::Hal& hal) { stage_.cost().log_misses(hal.times_fills()); }

    void start_task(const sw::ssa2::FrameInMemory& frame) {
        if (frame.task == task_) return;
        if (ahead_ && described_.load(std::memory_order_relaxed) !=
                          ahead_->handed)  // the driver's promise (Describer::ahead) broken
            throw std::logic_error("software stage: a task was left with candidates described ahead");
        stage_.begin_frame();                            // new DMA'd buffers: the cached lines are stale
        stage_.set_register_threshold(frame.threshold);  // the one the FHG compared with
        task_ = frame.task;
        records_ = 0;
    }

    // The stage on one candidate: its keypoint, its work and fills, the stage's counts after it.
    Result run_stage(uint32_t word, const sw::FrameBuffers& buffers) {
        Result r;
        const double start = stage_.cost().exact_cycles();
        const std::array<double, sw::kSteps> steps_before = stage_.cost().step_cycles();
        const uint64_t misses = stage_.cost().cache().misses();
        const uint64_t inconsistent = stage_.stats().inconsistent;
        try {
            r.keypoint = stage_.process(word, buffers);
        } catch (...) {
            r.error = std::current_exception();
        }
        if (stage_.stats().inconsistent != inconsistent) {
            const fhg::Candidate c = fhg::unpack_candidate(word);
            r.work.inconsistency = fmt::format(
                "candidate ({}, {}, size {}) is not above the threshold in the determinant "
                "buffer, though the FHG marked it: the buffer is corrupted",
                c.x, c.y, fhg::kSizes[size_t(c.size_index)]);
        }
        r.work.cycles = stage_.cost().take_cycles();
        for (size_t s = 0; s < sw::kSteps; ++s)
            if (const double c = stage_.cost().step_cycles()[s] - steps_before[s]; c > 0.5)
                r.work.steps.emplace_back(sw::step_name(sw::Step(s)), uint64_t(std::llround(c)));
        if (!stage_.cost().logs_misses()) r.work.untimed_fills = stage_.cost().cache().misses() - misses;
        r.work.lines.reserve(stage_.cost().misses().size());
        for (const sw::CostCounter::Miss& m : stage_.cost().misses()) {
            sw::LineTransfer& fill = r.work.lines.emplace_back();  // in place: see CostCounter::charge_misses
            fill.address = m.line;
            fill.at_cycle = uint64_t(std::llround(m.cycle - start));
        }
        stage_.cost().clear_misses();
        r.tally = tally();
        return r;
    }

    Result describe_now(sw::Hal& hal, uint32_t word, const sw::ssa2::FrameInMemory& frame) {
        std::lock_guard<std::mutex> lock(stage_mutex_);
        fills_for(hal);
        start_task(frame);
        const sw::FrameBuffers b = buffers(hal, frame);
        if (recorder_ && frame.task != recorded_task_) {
            recorder_->frame(b, params_);
            recorded_task_ = frame.task;
        }
        Result r = run_stage(word, b);
        if (recorder_ && !r.error) recorder_->word(word, r.keypoint);
        return r;
    }

    // The next candidate of the task described ahead; under stage_mutex_.
    void describe_next() {
        Ahead& a = *ahead_;
        const size_t k = described_.load(std::memory_order_relaxed);
        Result& r = a.results[k] = run_stage(a.words[k], a.buffers);
        a.stopped = r.error || !r.work.inconsistency.empty();
        described_.store(k + 1, std::memory_order_release);
    }

    // The worker's piece: one candidate ahead, if there is one.
    bool describe_ahead() {
        std::lock_guard<std::mutex> lock(stage_mutex_);
        if (!ahead_ || ahead_->stopped || described_.load(std::memory_order_relaxed) == ahead_->words.size())
            return false;
        describe_next();
        return true;
    }

    Result take_ahead(uint32_t word) {
        Ahead& a = *ahead_;
        const size_t k = a.handed++;
        if (k >= a.words.size() || a.words[k] != word)
            throw std::logic_error("software stage: the driver asked for a candidate out of the order it gave");
        if (described_.load(std::memory_order_acquire) <= k) {  // not done yet: here and now
            std::lock_guard<std::mutex> lock(stage_mutex_);
            while (described_.load(std::memory_order_relaxed) <= k) describe_next();
        }
        return std::move(a.results[k]);
    }

    // Each record has lines of its own (ring slots are whole lines, kRecordSlot), written once
    // and never read again: they leave the L1 as write-backs, counted when the record is
    // complete, without a fill (the driver allocates them, as with dcbz) [A].
    void write_back_record(const sw::ssa2::FrameInMemory& frame, sw::ssa2::Work& work) {
        const uint32_t at = frame.records + (records_++ % sw::ssa2::kRecordRing) * sw::ssa2::kRecordSlot;
        for (uint32_t line = at; line < at + sw::ssa2::kRecordBytes; line += line_bytes_)
            work.lines.push_back({line, work.cycles, true});
    }

    sw::StageParams params_;
    sw::SoftwareStage stage_;
    unsigned line_bytes_;

public:
    // The chip's APU FPU and what the other precision's prices would make of the same work.
    bool double_precision = false;
    std::array<double, sw::kUnits> other_precision_prices{};

private:
    std::unique_ptr<InputRecorder> recorder_;
    int recorded_task_ = -1;
    int task_ = -1;
    uint32_t records_ = 0;
    Tally handed_;
    Worker* worker_ = nullptr;
    std::mutex stage_mutex_;  // the stage and ahead_'s progress, between the driver's thread and the worker
    std::optional<Ahead> ahead_;
    // ahead_'s candidates described so far: written under stage_mutex_, read by the driver's
    // thread without it.
    std::atomic<size_t> described_{0};
};

}  // namespace

void calibrating_stage(bool on) { g_calibrating = on; }

void record_stage_inputs(const std::string& inputs, const std::string& expected) {
    g_record_inputs = inputs;
    g_record_expected = expected;
}

void share_worker(sw::ssa2::Describer& describer, Worker* worker) {
    if (auto* stage = dynamic_cast<StageDescriber*>(&describer)) stage->share_worker(worker);
}

namespace {

// The chip's FPU and the other precision's cycles for the same units of work (fills aside).
nlohmann::ordered_json fpu_report(const StageDescriber& stage, const sw::CostTotals& totals, double keypoints) {
    double work = 0, other = 0;
    for (size_t u = 0; u < sw::kUnits; ++u) {
        work += double(totals.units[u]) * stage.stage().cost().unit_cycles(sw::Unit(u));
        other += double(totals.units[u]) * stage.other_precision_prices[u];
    }
    return {{"precision", stage.double_precision ? "double" : "single"},
            {"work_cycles_per_keypoint", work / keypoints},
            {"other_precision", stage.double_precision ? "single" : "double"},
            {"other_work_cycles_per_keypoint", other / keypoints}};
}

}  // namespace

nlohmann::ordered_json describer_report(const sw::ssa2::Describer& describer) {
    const auto* stage = dynamic_cast<const StageDescriber*>(&describer);
    if (!stage) return nullptr;
    const sw::CostCounter& cost = stage->stage().cost();
    const auto& st = stage->handed().stats;
    const sw::CostTotals& totals = stage->handed().cost;
    const sw::CostBreakdown b = cost.breakdown(totals);
    const double keypoints = st.keypoints ? double(st.keypoints) : 1.0;
    nlohmann::ordered_json by_step = nlohmann::ordered_json::object(), per_keypoint = nlohmann::ordered_json::object();
    for (size_t k = 0; k < sw::kSteps; ++k) {
        by_step[sw::step_name(sw::Step(k))] = totals.steps[k];
        per_keypoint[sw::step_name(sw::Step(k))] = totals.steps[k] / keypoints;
    }
    nlohmann::ordered_json units = nlohmann::ordered_json::object();
    for (const sw::CostLine& line : b.lines)
        if (line.count) units[line.name] = {{"count", line.count}, {"cycles", line.cycles}};
    // What the PPC440 executed for this work, by the calibration's instructions per unit (one
    // stream: both precisions run the same code).
    const sw::UnitTable& table = sw::recorded_calibration().precision[0].haar[stage->rounded()];
    std::array<double, sw::kInsnClasses> mix{};
    double instructions = 0, libm_calls = 0;
    for (size_t u = 0; u < sw::kUnits; ++u) {
        const double n = double(totals.units[u]);
        instructions += n * table[u].instructions;
        libm_calls += n * table[u].libm_calls;
        for (size_t c = 0; c < sw::kInsnClasses; ++c) mix[c] += n * table[u].mix[c];
    }
    nlohmann::ordered_json classes = nlohmann::ordered_json::object();
    for (size_t c = 0; c < sw::kInsnClasses; ++c)
        if (mix[c] > 0) classes[sw::insn_class_name(sw::InsnClass(c))] = std::llround(mix[c]);
    return {{"candidates", st.candidates},
            {"keypoints", st.keypoints},
            {"rejected",
             {{"not_maximum", st.rejected_not_maximum},
              {"interpolation", st.rejected_interpolation},
              {"border", st.rejected_border}}},
            {"cycles_by_step", by_step},
            {"cycles_per_keypoint_by_step", per_keypoint},
            {"cycles_by_unit", units},
            {"total_cycles", b.total_cycles},
            {"instructions", std::llround(instructions)},
            {"instructions_by_class", classes},
            {"libm_calls", std::llround(libm_calls)},
            {"calibration", sw::recorded_calibration().provenance},
            {"fpu", fpu_report(*stage, totals, keypoints)},
            {"dcache",
             {{"accesses", b.cache_accesses},
              {"hits", b.cache_hits},
              {"misses", b.cache_misses},
              {"hit_rate", b.hit_rate}}}};
}

std::unique_ptr<sw::ssa2::Describer> make_describer(const Config& config, float threshold) {
    const surf::Params chip = chip_surf_params(config);  // the chip's software settings, read in one place
    sw::StageParams params;
    params.upright = chip.upright;
    params.haar = chip.haar;
    params.threshold = threshold;
    params.max_offset = chip.max_offset;
    params.descriptor = chip.descriptor;
    const sw::CostParams cost = cost_params(config, params.haar);
    // The calibration's own runs measure the price, so they run without it.
    if (!g_calibrating && params.descriptor == surf::DescriptorKind::msurf &&
        !(cost.unit_cycles[size_t(sw::Unit::msurf)] > 0))
        throw ConfigError(
            fmt::format("{}: msurf, but the calibration table has no price for M-SURF descriptors "
                        "(recalibrate with surfvp calibrate --msurf SCENARIO)",
                        config.where("surf.descriptor")));
    try {
        auto describer = std::make_unique<StageDescriber>(params, cost, cpu_params(config).line_bytes);
        const sw::PipelineParams pipeline = pipeline_params(config);
        describer->double_precision = pipeline.double_precision > 0.5;
        describer->other_precision_prices = sw::unit_prices(
            params.haar, pipeline_params(config.with(
                             {{"fpu.precision", describer->double_precision ? "single" : "double"}}, "the other FPU")));
        return describer;
    } catch (const std::invalid_argument& e) {
        throw ConfigError(e.what());
    }
}

}  // namespace surfvp
