#include "platform/workload/describer.h"

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <fmt/format.h>
#include <vector>

#include "models/fhg/fhg_regs.h"
#include "models/fhg/local_max_finder.h"
#include "platform/soc.h"
#include "platform/workload/workload.h"
#include "models/common/byte_order.h"
#include "sw/cpu_cost/calibration.h"
#include "sw/cpu_cost/calibration_dump.h"
#include "sw/stage/software_stage.h"

namespace surfvp {
namespace {

sw::PipelineParams pipeline_params(const Config& c) {
    sw::PipelineParams p;
    for (const sw::PipelineKnob& k : sw::pipeline_knobs()) {
        const std::string unit = k.unit;
        p.*k.field = unit == "switch" ? (c.choice(k.key) == "on" ? 1.0 : 0.0)
                     : unit == "count" ? double(c.count(k.key))
                                       : double(c.cycles(k.key));
    }
    return p;
}

sw::CostParams cost_params(const Config& c, surf::HaarMode haar) {
    sw::CostParams p = sw::calibrated_cost_params(haar, pipeline_params(c));
    p.miss_cycles = 0;  // the platform times each fill on the memory path (Hal::compute)
    p.cache.size_bytes = uint32_t(c.bytes("cpu.dcache_size").n);
    p.cache.line_bytes = uint32_t(c.bytes("cpu.cache_line").n);
    p.cache.ways = uint32_t(c.count("cpu.dcache_ways"));
    p.cache.replacement = c.choice("cpu.dcache_replacement") == "lru" ? sw::Replacement::lru : sw::Replacement::round_robin;
    return p;
}

// `surfvp calibrate`: where the describers made from now on record what the stage saw.
std::string g_record_inputs, g_record_expected;

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
        header_ = {dump::kMagic, uint32_t(b.width), uint32_t(b.height), b.det_frac_bits, b.det_bytes,
                   p.haar == surf::HaarMode::rounded, p.upright, p.threshold, b.integral_address,
                   b.determinants_address, uint32_t(b.integral_stride * b.height), uint32_t(det_bytes), 0};
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
class StageDescriber : public sw::ssa2::Describer {
public:
    StageDescriber(const sw::StageParams& params, const sw::CostParams& cost, unsigned line_bytes)
        : params_(params), stage_(params, sw::CostCounter(cost)), line_bytes_(line_bytes) {
        stage_.cost().log_misses(true);
        if (!g_record_inputs.empty()) recorder_ = std::make_unique<InputRecorder>(g_record_inputs, g_record_expected);
    }

    std::optional<surf::Keypoint> describe(sw::Hal& hal, uint32_t word, const sw::ssa2::FrameInMemory& frame,
                                           sw::ssa2::Work& work) override {
        if (frame.task != task_) {  // new DMA'd buffers: the cached lines are stale
            stage_.begin_frame();
            stage_.set_register_threshold(frame.threshold);  // the one the FHG compared with
            task_ = frame.task;
            records_ = 0;
        }
        const size_t integral_bytes = size_t(frame.width) * frame.height * 4;
        const size_t det_bytes = size_t(fhg_regs::buffer_bytes(uint32_t(frame.width), uint32_t(frame.height), frame.det_bytes));
        const sw::FrameBuffers buffers{hal.map(frame.integral, integral_bytes), frame.integral, size_t(frame.width) * 4,
                                       hal.map(frame.determinants, det_bytes), frame.determinants, frame.width,
                                       frame.height, frame.det_frac_bits, frame.det_bytes};
        if (recorder_ && frame.task != recorded_task_) {
            recorder_->frame(buffers, params_);
            recorded_task_ = frame.task;
        }
        const double start = stage_.cost().exact_cycles();
        const uint64_t inconsistent = stage_.stats().inconsistent;
        auto keypoint = stage_.process(word, buffers);
        if (stage_.stats().inconsistent != inconsistent) {
            const fhg::Candidate c = fhg::unpack_candidate(word);
            work.inconsistency = fmt::format("candidate ({}, {}, size {}) is not above the threshold in the determinant "
                                             "buffer, though the FHG marked it: the buffer is corrupted",
                                             c.x, c.y, fhg::kSizes[size_t(c.size_index)]);
        }
        if (recorder_) recorder_->word(word, keypoint);
        work.cycles = stage_.cost().take_cycles();
        for (const sw::CostCounter::Miss& m : stage_.cost().misses())
            work.lines.push_back({m.line, uint64_t(std::llround(m.cycle - start)), false});
        stage_.cost().clear_misses();
        if (keypoint) write_back_record(frame, work);
        return keypoint;
    }

    const sw::SoftwareStage& stage() const { return stage_; }
    bool rounded() const { return params_.haar == surf::HaarMode::rounded; }

private:
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
    std::unique_ptr<InputRecorder> recorder_;
    int recorded_task_ = -1;
    int task_ = -1;
    uint32_t records_ = 0;
};

}  // namespace

void record_stage_inputs(const std::string& inputs, const std::string& expected) {
    g_record_inputs = inputs;
    g_record_expected = expected;
}

nlohmann::ordered_json describer_report(const sw::ssa2::Describer& describer) {
    const auto* stage = dynamic_cast<const StageDescriber*>(&describer);
    if (!stage) return nullptr;
    const sw::SoftwareStage& s = stage->stage();
    const auto& st = s.stats();
    const sw::CostCounter& cost = s.cost();
    const sw::CostBreakdown b = cost.breakdown();
    const double keypoints = st.keypoints ? double(st.keypoints) : 1.0;
    nlohmann::ordered_json by_step = nlohmann::ordered_json::object(), per_keypoint = nlohmann::ordered_json::object();
    for (size_t k = 0; k < sw::kSteps; ++k) {
        by_step[sw::step_name(sw::Step(k))] = cost.step_cycles()[k];
        per_keypoint[sw::step_name(sw::Step(k))] = cost.step_cycles()[k] / keypoints;
    }
    nlohmann::ordered_json units = nlohmann::ordered_json::object();
    for (const sw::CostLine& line : b.lines)
        if (line.count) units[line.name] = {{"count", line.count}, {"cycles", line.cycles}};
    // What the PPC440 executed for this work, by the calibration's instructions per unit.
    const sw::UnitTable& table = sw::recorded_calibration().haar[stage->rounded()];
    std::array<double, sw::kInsnClasses> mix{};
    double instructions = 0, libm_calls = 0;
    for (size_t u = 0; u < sw::kUnits; ++u) {
        const double n = double(cost.counted(sw::Unit(u)));
        instructions += n * table[u].instructions;
        libm_calls += n * table[u].libm_calls;
        for (size_t c = 0; c < sw::kInsnClasses; ++c) mix[c] += n * table[u].mix[c];
    }
    nlohmann::ordered_json classes = nlohmann::ordered_json::object();
    for (size_t c = 0; c < sw::kInsnClasses; ++c)
        if (mix[c] > 0) classes[sw::insn_class_name(sw::InsnClass(c))] = std::llround(mix[c]);
    return {{"candidates", st.candidates},
            {"keypoints", st.keypoints},
            {"rejected", {{"not_maximum", st.rejected_not_maximum}, {"interpolation", st.rejected_interpolation},
                          {"border", st.rejected_border}}},
            {"cycles_by_step", by_step},
            {"cycles_per_keypoint_by_step", per_keypoint},
            {"cycles_by_unit", units},
            {"total_cycles", b.total_cycles},
            {"instructions", std::llround(instructions)},
            {"instructions_by_class", classes},
            {"libm_calls", std::llround(libm_calls)},
            {"calibration", sw::recorded_calibration().provenance},
            {"dcache", {{"accesses", b.cache_accesses}, {"hits", b.cache_hits}, {"misses", b.cache_misses},
                        {"hit_rate", b.hit_rate}}}};
}

std::unique_ptr<sw::ssa2::Describer> make_describer(const Config& config, float threshold) {
    const surf::Params chip = chip_surf_params(config);  // the chip's software settings, read in one place
    sw::StageParams params;
    params.upright = chip.upright;
    params.haar = chip.haar;
    params.threshold = threshold;
    params.max_offset = chip.max_offset;
    try {
        return std::make_unique<StageDescriber>(params, cost_params(config, params.haar),
                                                unsigned(config.bytes("cpu.cache_line").n));
    } catch (const std::invalid_argument& e) {
        throw ConfigError(e.what());
    }
}

}  // namespace surfvp
