#include "describer.h"

#include <cmath>

#include "models/fhg/fhg_regs.h"
#include "soc.h"
#include "sw/stage/software_stage.h"

namespace surfvp {
namespace {

sw::CostParams cost_params(const Config& c) {
    sw::CostParams p;
    p.int_op_cycles = double(c.cycles("cpu.int_op"));
    p.branch_cycles = double(c.cycles("cpu.branch"));
    p.load_cycles = double(c.cycles("cpu.load"));
    p.miss_cycles = 0;  // the platform times each fill on the memory path (Hal::compute)
    p.fpu_clock_ratio = double(c.count("cpu.fpu_ratio"));
    p.fpu_issue_cycles = double(c.cycles("cpu.fpu_issue"));
    p.fpu_dependent_fraction = c.real("cpu.fpu_dependent_fraction");
    p.fadd_latency = double(c.cycles("fpu.fadd"));
    p.fmul_latency = double(c.cycles("fpu.fmul"));
    p.fmadd_latency = double(c.cycles("fpu.fmadd"));
    p.fdiv_latency = double(c.cycles("fpu.fdiv"));
    p.fsqrt_latency = double(c.cycles("fpu.fsqrt"));
    p.fcmp_latency = double(c.cycles("fpu.fcmp"));
    p.fmove_latency = double(c.cycles("fpu.fmove"));
    p.fload_latency = double(c.cycles("fpu.fload"));
    p.fstore_latency = double(c.cycles("fpu.fstore"));
    p.fcvt_cycles = double(c.cycles("cpu.int_float_convert"));
    p.call_cycles = double(c.cycles("cpu.call"));
    p.cache.size_bytes = uint32_t(c.bytes("cpu.dcache_size").n);
    p.cache.line_bytes = uint32_t(c.bytes("cpu.cache_line").n);
    p.cache.ways = uint32_t(c.count("cpu.dcache_ways"));
    p.cache.replacement = c.choice("cpu.dcache_replacement") == "lru" ? sw::Replacement::lru : sw::Replacement::round_robin;
    return p;
}

// libSSA2's phase 4 on the software stage: the frame's buffers read in place (DMI), the
// stage's counted work and its L1 fills handed back for the CPU to spend, and the described
// keypoint's record written back to the task's ring.
class StageDescriber : public sw::ssa2::Describer {
public:
    StageDescriber(const sw::StageParams& params, unsigned line_bytes) : stage_(params), line_bytes_(line_bytes) {
        stage_.cost().log_misses(true);
    }

    std::optional<surf::Keypoint> describe(sw::Hal& hal, uint32_t word, const sw::ssa2::FrameInMemory& frame,
                                           sw::ssa2::Work& work) override {
        if (frame.task != task_) {  // new DMA'd buffers: the cached lines are stale
            stage_.begin_frame();
            task_ = frame.task;
            records_ = 0;
        }
        const size_t integral_bytes = size_t(frame.width) * frame.height * 4;
        const size_t det_bytes = size_t((frame.width + 1) / 2) * ((frame.height + 1) / 2) * fhg_regs::record_bytes(frame.det_bytes);
        const sw::FrameBuffers buffers{hal.map(frame.integral, integral_bytes), frame.integral, size_t(frame.width) * 4,
                                       hal.map(frame.determinants, det_bytes), frame.determinants, frame.width,
                                       frame.height, frame.det_frac_bits, frame.det_bytes};
        const double start = stage_.cost().exact_cycles();
        auto keypoint = stage_.process(word, buffers);
        work.cycles = stage_.cost().take_cycles();
        for (const sw::CostCounter::Miss& m : stage_.cost().misses())
            work.lines.push_back({m.line, uint64_t(std::llround(m.cycle - start)), false});
        stage_.cost().clear_misses();
        if (keypoint) write_back_record(frame, work);
        return keypoint;
    }

    const sw::SoftwareStage& stage() const { return stage_; }

private:
    // Each record has lines of its own (ring slots are whole lines, kRecordSlot), written once
    // and never read again: they leave the L1 as write-backs, counted when the record is
    // complete, without a fill (the driver allocates them, as with dcbz) [A].
    void write_back_record(const sw::ssa2::FrameInMemory& frame, sw::ssa2::Work& work) {
        const uint32_t at = frame.records + (records_++ % sw::ssa2::kRecordRing) * sw::ssa2::kRecordSlot;
        for (uint32_t line = at; line < at + sw::ssa2::kRecordBytes; line += line_bytes_)
            work.lines.push_back({line, work.cycles, true});
    }

    sw::SoftwareStage stage_;
    unsigned line_bytes_;
    int task_ = -1;
    uint32_t records_ = 0;
};

}  // namespace

nlohmann::ordered_json describer_report(const sw::ssa2::Describer& describer) {
    const auto* stage = dynamic_cast<const StageDescriber*>(&describer);
    if (!stage) return nullptr;
    const sw::SoftwareStage& s = stage->stage();
    const auto& st = s.stats();
    const auto& ph = s.phase_cycles();
    const sw::CostBreakdown b = s.cost().breakdown();
    nlohmann::ordered_json kinds = nlohmann::ordered_json::object();
    for (const sw::CostLine& line : b.lines)
        if (line.count) kinds[line.name] = {{"count", line.count}, {"cycles", line.cycles}};
    const double keypoints = st.keypoints ? double(st.keypoints) : 1.0;
    return {{"candidates", st.candidates},
            {"keypoints", st.keypoints},
            {"rejected", {{"not_maximum", st.rejected_not_maximum}, {"interpolation", st.rejected_interpolation},
                          {"border", st.rejected_border}}},
            {"cycles_per_keypoint_by_step", {{"check", ph.check / keypoints}, {"interpolation", ph.interpolation / keypoints},
                                             {"laplacian", ph.laplacian / keypoints}, {"orientation", ph.orientation / keypoints},
                                             {"descriptor", ph.descriptor / keypoints}}},
            {"cycles_by_kind", kinds},
            {"total_cycles", b.total_cycles},
            {"dcache", {{"accesses", b.cache_accesses}, {"hits", b.cache_hits}, {"misses", b.cache_misses},
                        {"hit_rate", b.hit_rate}}}};
}

std::unique_ptr<sw::ssa2::Describer> make_describer(const Config& config, float threshold) {
    sw::StageParams params;
    params.upright = config.choice("surf.upright") == "on";
    params.haar = config.choice("surf.haar") == "exact" ? surf::HaarMode::exact : surf::HaarMode::rounded;
    params.threshold = threshold;
    params.cost = cost_params(config);
    try {
        return std::make_unique<StageDescriber>(params, unsigned(config.bytes("cpu.cache_line").n));
    } catch (const std::invalid_argument& e) {
        throw ConfigError(e.what());
    }
}

}  // namespace surfvp
