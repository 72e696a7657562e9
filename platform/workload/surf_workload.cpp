// The SURF workload: frames in memory, libSSA2 driving the accelerators, the software stage
// describing the candidates; judged on frame rate against the budget. The frames come from
// frame_source, the keypoint files go to keypoint_sink, the feature quality is
// surf_evaluation's.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <yaml-cpp/binary.h>

#include "models/common/zeroed_memory.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/hessian_core.h"
#include "models/host/worker.h"
#include "platform/address_map.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"
#include "platform/workload/describer.h"
#include "platform/workload/frame_source.h"
#include "platform/workload/keypoint_sink.h"
#include "platform/workload/surf_evaluation.h"
#include "platform/workload/surf_settings.h"
#include "platform/workload/workload.h"
#include "sw/libssa2/libssa2.h"
#include "sw/media/media.h"
#include "sw/surf/surf.h"

namespace surfvp {
namespace {

constexpr uint64_t kPage = 4096;
constexpr uint32_t kOutsideMemory = 0xF000'0000;  // a dma_outside_memory fault's buffer: no DDR there
uint64_t round_up(uint64_t v) { return (v + kPage - 1) / kPage * kPage; }

// Where a run's buffers are in memory: one set of frame, integral image, determinant and
// descriptor buffers per task in flight (frames arrive in their set's buffer as tasks start, so
// memory does not grow with the number of frames). Throws ConfigError when they do not fit
// memory.size.
struct Layout {
    uint64_t image_bytes, integral_bytes, det_bytes, slot_bytes, slots_base;
};

Layout layout_for(const Config& c, int width, int height) {
    Layout l{};
    l.image_bytes = round_up(uint64_t(width) * height);
    l.integral_bytes = round_up(uint64_t(width) * height * 4);
    const uint32_t det = fhg_regs::det_bytes_for(fhg_params(c).precision.det_bits);
    l.det_bytes = round_up(fhg_regs::buffer_bytes(uint32_t(width), uint32_t(height), det));
    l.slot_bytes = l.image_bytes + l.integral_bytes + l.det_bytes +
                   round_up(uint64_t(sw::ssa2::kRecordRing) * sw::ssa2::kRecordSlot);
    l.slots_base = 0x0010'0000;
    const uint64_t sets = surf_settings(c).tasks_in_flight;
    const uint64_t end = l.slots_base + sets * l.slot_bytes;
    const Bytes memory = memory_params(c).size;
    if (end > memory.n)
        throw ConfigError(
            fmt::format("{}: {} buffer sets (surf.tasks_in_flight, from {}) for frames of {}x{} need {} of "
                        "memory, memory.size is {}",
                        c.where("memory.size"), sets, c.source_of("surf.tasks_in_flight"), width, height,
                        format_bytes(Bytes{end}), format_bytes(memory)));
    return l;
}

// The float reference on frame 0, limited to the chip's two octaves at step 1: the threshold,
// and how many maxima frame 0 has (fewer than the target: the threshold is 0, every maximum).
struct Calibration {
    float threshold = 0;
    size_t maxima = 0;
};

Calibration calibrate(const Config& c, const cv::Mat& frame) {
    const SurfWorkloadSettings s = surf_settings(c);
    if (s.target_keypoints == 0) return {float(s.threshold), 0};
    static std::map<std::string, std::vector<float>> ranked;
    const surf::Params p = chip_surf_params(c);
    const std::string key = fmt::format("{}|{}|{}", source_key(c), p.upright, p.max_offset);
    auto it = ranked.find(key);
    if (it == ranked.end()) it = ranked.emplace(key, surf::stored_ranked_responses(frame, p)).first;
    return {surf::threshold_for_rank(it->second, int(s.target_keypoints)), it->second.size()};
}

// What is kept of a frame once it is reported: its task (times, outcome, counts) and, for the
// frames the evaluation or the report's picture need, its keypoints; the others are in their
// keypoint file.
struct FrameResult {
    sw::ssa2::Task task;
    size_t keypoint_count = 0;
    surf::Keypoints keypoints;
    bool reported = false;
};

class SurfWorkload : public Workload {
public:
    explicit SurfWorkload(const Config& c)
        : config_(c),
          settings_(surf_settings(c)),
          accelerators_(run_settings(c).accelerators),
          source_(load_source(c)),
          calibration_(calibrate(c, source_.first)),
          threshold_(calibration_.threshold),
          describer_(make_describer(c, threshold_)),
          results_(source_.count) {
        width_ = source_.first.cols;
        height_ = source_.first.rows;
        const cv::Size largest = source_.largest();  // frames of a folder or list may differ: buffers fit the largest
        layout_ = layout_for(c, largest.width, largest.height);
        const fhg::HessianCore core(fhg_params(c).precision);
        driver_.intc_base = map::intc.base;
        for (unsigned k = 0; k < accelerators_; ++k)
            driver_.accelerators.push_back({map::iig_base(k), map::fhg_base(k), map::irq::iig(k), map::irq::fhg(k)});
        for (uint64_t set = 0, at = layout_.slots_base; set < settings_.tasks_in_flight;
             ++set, at += layout_.slot_bytes)
            driver_.buffers.push_back(
                {uint32_t(at), uint32_t(at + layout_.image_bytes),
                 uint32_t(at + layout_.image_bytes + layout_.integral_bytes),
                 uint32_t(at + layout_.image_bytes + layout_.integral_bytes + layout_.det_bytes)});
        driver_.fifo_irq_level = settings_.fifo_irq_level;
        driver_.threshold = core.from_float(threshold_);
        if (settings_.track) driver_.keypoint_target = uint32_t(settings_.target_keypoints);
        to_float_ = [core](int32_t t) { return core.to_float(t); };
        driver_.watchdog_ps = settings_.watchdog.ps;
        driver_.spurious_irq_limit = settings_.spurious_irq_limit;
        budget_fps_ = settings_.budget_fps;
        // A frame rate needs one whole round of the pairs after the first frame.
        if (budget_fps_ > 0 && source_.count <= accelerators_)
            throw ConfigError(
                fmt::format("surf.frames: {} frames cannot give a frame rate with {} accelerator pair(s): "
                            "the steady-state rate needs {}; set more frames or budget.fps = 0",
                            source_.count, accelerators_, accelerators_ + 1));
        cpu_hz_ = cpu_params(c).clock.hz;
    }

    void attach_memory(const Backdoor& memory) override { memory_ = memory; }
    void inject(FaultPlan& faults) override { faults_ = &faults; }
    void share_worker(Worker* worker) override {
        keypoint_files_.use_thread(worker != nullptr);  // with a second thread (run.parallel), one of their own
        surfvp::share_worker(*describer_, worker);
    }
    void write_into(const std::string& dir) override { keypoint_files_.write_into(dir); }
    std::vector<std::string> files_written() override { return keypoint_files_.files_written(); }

    Ppc440::Software software() override {
        return [this](sw::Hal& hal) {
            software_start_ = std::chrono::steady_clock::now();
            std::vector<sw::ssa2::Task> tasks(source_.count);
            for (size_t i = 0; i < tasks.size(); ++i) {
                tasks[i].width = source_.sizes[i].width;
                tasks[i].height = source_.sizes[i].height;
            }
            if (faults_) give_buffers_outside_memory(tasks, hal.time_ps());
            sw::ssa2::Driver driver(hal, driver_, *describer_);
            FrameStream stream(config_, source_);
            driver.run(
                tasks, [&](const sw::ssa2::Task& task) { deliver(stream.frame(size_t(task.id)), task); },
                [this](const sw::ssa2::Task& task, surf::Keypoints&& keypoints) {
                    reported(task, std::move(keypoints));
                });
            accelerator_time_ = driver.accelerator_time();
            recovery_ = driver.recovery();
        };
    }

    Progress progress() const override { return {done_, source_.count, "frames"}; }

    std::vector<Check> checks() const override {
        std::vector<Check> checks;
        std::vector<std::string> failures;
        size_t lost_to_faults = 0, done = 0;
        for (const FrameResult& r : results_) {
            done += r.task.phase == sw::ssa2::Phase::done;
            if (r.task.phase != sw::ssa2::Phase::failed) continue;
            if (struck_by_fault(r.task.id))
                ++lost_to_faults;
            else
                failures.push_back(fmt::format("frame {}: {}", r.task.id, r.task.error));
        }
        const std::string lost = lost_to_faults ? fmt::format("; {} lost to injected faults", lost_to_faults) : "";
        checks.push_back({"every frame processed", failures.empty() && done + lost_to_faults == source_.count,
                          failures.empty() ? fmt::format("{} of {} frames{}", done, source_.count, lost)
                                           : fmt::format("{}", fmt::join(failures, "; "))});
        if (faults_) checks.push_back(fault_check());
        if (const uint64_t target = settings_.target_keypoints; target > 0)
            checks.push_back(
                {"keypoint target reachable", calibration_.maxima > target,
                 calibration_.maxima > target
                     ? fmt::format("frame 0 has {} maxima for surf.target_keypoints = {}", calibration_.maxima, target)
                     : fmt::format("frame 0 has only {} maxima, not more than surf.target_keypoints = {}: the "
                                   "threshold is 0 and every maximum is kept; lower the target",
                                   calibration_.maxima, target),
                 true});
        if (budget_fps_ > 0) {
            const double fps = throughput();
            checks.push_back({"frame-rate budget", fps >= budget_fps_,
                              fmt::format("{:.2f} frames/s against {:.2f}", fps, budget_fps_), true});
        }
        return checks;
    }

    nlohmann::ordered_json summary() const override;
    nlohmann::ordered_json report() const override;
    std::string first_frame_svg() const override;

    // Each frame's hardware phases on its accelerator's track and its descriptors on the
    // CPU's: frames overlapping across the chip; a flow from the CPU's handling of the FHG's
    // interrupt to the descriptors it starts. In the VCD, a marker at each frame's start.
    void trace(Tracer& tracer) const override {
        for (const FrameResult& r : results_)
            if (r.reported && r.task.t_start > 0) tracer.marker(r.task.t_start, fmt::format("frame {}", r.task.id));
        if (!tracer.perfetto_on()) return;
        std::vector<int> hardware;
        for (size_t k = 0; k < driver_.accelerators.size(); ++k)
            hardware.push_back(tracer.track("frames", fmt::format("accelerator {} (integral + determinants)", k)));
        const int descriptors = tracer.track("frames", "cpu (descriptors)");
        const int cpu = tracer.track_of("cpu", "cpu");
        auto at = [](uint64_t ps) { return sc_core::sc_time(double(ps), sc_core::SC_PS); };
        for (const FrameResult& r : results_) {
            const auto& t = r.task;
            if (!r.reported || t.t_determinants == 0) continue;
            TraceArgs args;
            args.number("frame", t.id).number("keypoints", double(r.keypoints.size()));
            if (t.phase == sw::ssa2::Phase::failed) args.text("failed", t.error);
            tracer.slice(hardware[size_t(t.id) % hardware.size()], "integral + determinants", at(t.t_start),
                         at(t.t_determinants), args);
            if (t.phase != sw::ssa2::Phase::done) continue;
            tracer.slice(descriptors, "descriptors", at(t.t_determinants), at(t.t_done), args);
            const uint64_t flow = tracer.flow_id();
            tracer.flow(cpu, at(t.t_determinants), flow, Tracer::Flow::begin, "continues the frame");
            tracer.flow(descriptors, at(t.t_determinants), flow, Tracer::Flow::end, "continues the frame");
        }
    }

private:
    void deliver(const cv::Mat& frame, const sw::ssa2::Task& task);
    void reported(const sw::ssa2::Task& task, surf::Keypoints&& keypoints);
    bool kept(size_t frame) const { return frame == 0 || evaluation_needs(config_, frame); }  // 0: the picture

    double throughput() const;
    nlohmann::ordered_json evaluation() const {
        if (done_ != source_.count) return nlohmann::ordered_json::object();
        std::vector<const surf::Keypoints*> keypoints;
        for (const FrameResult& r : results_) keypoints.push_back(&r.keypoints);
        return evaluate(config_, source_, keypoints);
    }
    void give_buffers_outside_memory(std::vector<sw::ssa2::Task>& tasks, uint64_t now_ps) const;
    bool struck_by_fault(int frame) const;
    bool detected(const Fault& fault) const;
    bool recovered(const Fault& fault) const;
    Check fault_check() const;
    nlohmann::ordered_json fault_report() const;
    // How the threshold was chosen (calibrate() above, libSSA2's keypoint-count control).
    std::string threshold_rule() const {
        const std::string rule =
            threshold_rule_text(config_, "of the float reference with the chip's settings (2 octaves of 4 intervals)");
        return driver_.keypoint_target ? rule + "; each frame's is in frames.csv" : rule;
    }
    std::function<double(int32_t)> to_float_;  // the FHG's determinant units -> the float reference's

    const Config& config_;
    const SurfWorkloadSettings settings_;
    const unsigned accelerators_;  // soc.accelerators
    const SourceFrames& source_;
    Calibration calibration_;
    float threshold_;
    std::unique_ptr<sw::ssa2::Describer> describer_;
    std::vector<FrameResult> results_;
    sw::ssa2::DriverConfig driver_;
    int width_ = 0, height_ = 0;
    Layout layout_{};
    uint64_t done_ = 0;
    // The host's wall clock: when the software started, and how long after it each frame was
    // reported (in the order they were): the simulator's own speed, frame by frame.
    std::chrono::steady_clock::time_point software_start_{};
    std::vector<double> frame_wall_s_;
    FaultPlan* faults_ = nullptr;
    Backdoor memory_;
    KeypointSink keypoint_files_;
    sw::ssa2::Driver::Recovery recovery_;
    double budget_fps_ = 0, cpu_hz_ = 0;
    std::vector<sw::ssa2::AcceleratorTime> accelerator_time_;
};

// Steady state: frames finished per second over the last whole rounds of the accelerator
// pairs (with k pairs frames finish in bunches of k, so the span covers a multiple of k
// frames: a part of a round would count a bunch without its gap).
double SurfWorkload::throughput() const {
    std::vector<uint64_t> ends;
    for (const FrameResult& r : results_)
        if (r.reported && r.task.phase == sw::ssa2::Phase::done) ends.push_back(r.task.t_done);
    const size_t k = driver_.accelerators.size();
    if (ends.size() < k + 1) return 0;
    std::sort(ends.begin(), ends.end());
    const size_t span = (ends.size() - 1) / k * k;
    return double(span) / (double(ends.back() - ends[ends.size() - 1 - span]) * 1e-12);
}

// dma_outside_memory: the driver is given a buffer where there is no memory for that frame
// (when the software starts).
void SurfWorkload::give_buffers_outside_memory(std::vector<sw::ssa2::Task>& tasks, uint64_t now_ps) const {
    for (size_t i = 0; i < faults_->faults().size(); ++i) {
        const Fault& f = faults_->faults()[i];
        if (f.kind != FaultKind::dma_outside_memory) continue;
        (f.block == "iig" ? tasks[f.frame].integral : tasks[f.frame].determinants) = kOutsideMemory;
        faults_->strike_in_software(i, now_ps);
    }
}

bool SurfWorkload::struck_by_fault(int frame) const {
    if (!faults_) return false;
    const auto& all = faults_->faults();
    return std::any_of(all.begin(), all.end(), [&](const Fault& f) { return f.fired && f.struck_frame == frame; });
}

// The driver noticed: the frame it struck failed, or the driver recovered from it (a lost
// interrupt found by the watchdog).
bool SurfWorkload::detected(const Fault& f) const {
    if (!f.fired || f.struck_frame < 0 || size_t(f.struck_frame) >= results_.size()) return false;
    const sw::ssa2::Task& t = results_[size_t(f.struck_frame)].task;
    return t.phase == sw::ssa2::Phase::failed || !t.incidents.empty();
}

// Detected, and the frame went on, or its accelerator pair finished a later frame well.
bool SurfWorkload::recovered(const Fault& f) const {
    if (!detected(f)) return false;
    const sw::ssa2::Task& struck = results_[size_t(f.struck_frame)].task;
    if (struck.phase == sw::ssa2::Phase::done) return true;
    return std::any_of(results_.begin(), results_.end(), [&](const FrameResult& r) {
        return r.task.phase == sw::ssa2::Phase::done && r.task.described_on == struck.described_on &&
               r.task.t_start > struck.t_start;
    });
}

Check SurfWorkload::fault_check() const {
    std::vector<std::string> missed;
    for (const Fault& f : faults_->faults()) {
        if (!f.fired)
            missed.push_back(f.describe() + " never struck (" + f.origin + ")");
        else if (!detected(f))
            missed.push_back(f.describe() + " went undetected");
    }
    const size_t n = faults_->faults().size();
    return {"every injected fault detected", missed.empty(),
            missed.empty() ? fmt::format("{} of {} faults struck and were detected", n, n)
                           : fmt::format("{}", fmt::join(missed, "; "))};
}

nlohmann::ordered_json SurfWorkload::fault_report() const {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    size_t injected = 0, detected_n = 0, recovered_n = 0, lost = 0;
    for (const Fault& f : faults_->faults()) {
        nlohmann::ordered_json j = {{"fault", f.describe()}, {"origin", f.origin}, {"struck", f.fired}};
        if (f.fired) {
            ++injected;
            j["at_ms"] = double(f.fired_ps) * 1e-9;
            j["frame"] = f.struck_frame;
            j["detected"] = detected(f);
            j["recovered"] = recovered(f);
            detected_n += detected(f);
            recovered_n += recovered(f);
            if (f.struck_frame >= 0 && size_t(f.struck_frame) < results_.size()) {
                const sw::ssa2::Task& t = results_[size_t(f.struck_frame)].task;
                j["outcome"] = t.phase == sw::ssa2::Phase::failed ? "frame failed: " + t.error
                               : t.incidents.empty()              ? std::string("frame done, nothing noticed")
                                                     : "frame done: " + fmt::format("{}", fmt::join(t.incidents, "; "));
            }
        }
        list.push_back(j);
    }
    for (const FrameResult& r : results_) lost += r.task.phase == sw::ssa2::Phase::failed;
    return {{"given", faults_->faults().size()},
            {"injected", injected},
            {"detected", detected_n},
            {"tasks_lost", lost},
            {"recovered", recovered_n},
            {"driver",
             {{"watchdog_expiries", recovery_.watchdog_expiries},
              {"spurious_interrupts", recovery_.spurious_interrupts},
              {"pair_resets", recovery_.pair_resets}}},
            {"list", list}};
}

nlohmann::ordered_json SurfWorkload::summary() const {
    double latency = 0, integral = 0, determinants = 0, describe = 0, keypoints = 0, cycles = 0;
    size_t n = 0, min_kp = SIZE_MAX, max_kp = 0;
    for (const FrameResult& r : results_) {
        if (r.task.phase != sw::ssa2::Phase::done) continue;
        const auto& t = r.task;
        latency += double(t.t_done - t.t_start);
        integral += double(t.t_integral - t.t_start);
        determinants += double(t.t_determinants - t.t_start);
        describe += double(t.t_done - t.t_determinants);
        keypoints += double(r.keypoint_count);
        cycles += double(t.descriptor_cycles);
        min_kp = std::min(min_kp, r.keypoint_count);
        max_kp = std::max(max_kp, r.keypoint_count);
        ++n;
    }
    const double per = n ? 1.0 / double(n) : 0;
    const double fps = throughput();
    nlohmann::ordered_json budget = nullptr;
    if (budget_fps_ > 0) budget = {{"fps", budget_fps_}, {"met", fps >= budget_fps_}};
    nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
    for (const auto& a : accelerator_time_)
        pairs.push_back({{"working_s", a.working_ps * 1e-12},
                         {"waiting_for_buffers_s", a.waiting_for_buffers_ps * 1e-12},
                         {"idle_s", a.idle_ps * 1e-12}});
    std::vector<std::string> sizes;  // frames of a folder or list may differ in size
    for (const cv::Size& f : source_.sizes)
        if (const std::string wxh = fmt::format("{}x{}", f.width, f.height);
            std::find(sizes.begin(), sizes.end(), wxh) == sizes.end())
            sizes.push_back(wxh);
    nlohmann::ordered_json out = {
        {"image", {{"width", width_}, {"height", height_}}},
        {"frames", source_.count},
        {"frames_done", n},
        {"throughput_fps", fps},
        {"latency_ms", latency * per * 1e-9},
        {"keypoints_per_frame", keypoints * per},
        {"keypoints_per_frame_range", {n ? min_kp : 0, max_kp}},
        {"threshold", threshold_},
        {"threshold_rule", threshold_rule()},
        {"budget", budget},
        {"phases_ms",
         {{"integral_image", integral * per * 1e-9},
          {"determinants", determinants * per * 1e-9},
          {"descriptors", describe * per * 1e-9}}},
        {"software_time_per_keypoint_us", keypoints > 0 ? cycles / keypoints / cpu_hz_ * 1e6 : 0.0},
        {"software_cycles_per_keypoint", keypoints > 0 ? cycles / keypoints : 0.0},
        {"accelerator_pairs", pairs}};
    if (sizes.size() > 1) out["frame_sizes"] = sizes;  // "image" is frame 0's
    if (faults_) out["faults"] = fault_report();
    out["frame_wall_s"] = frame_wall_s_;  // a wall-clock field (run.cpp)
    return out;
}

nlohmann::ordered_json SurfWorkload::report() const {
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    for (const FrameResult& r : results_) {
        const auto& t = r.task;
        nlohmann::ordered_json f = {{"frame", t.id},
                                    {"candidates", t.candidate_count},
                                    {"keypoints", r.keypoint_count},
                                    {"start_ms", t.t_start * 1e-9},
                                    {"integral_done_ms", t.t_integral * 1e-9},
                                    {"determinants_done_ms", t.t_determinants * 1e-9},
                                    {"done_ms", t.t_done * 1e-9},
                                    {"descriptor_cycles", t.descriptor_cycles},
                                    {"threshold", to_float_(t.threshold)}};
        if (t.phase == sw::ssa2::Phase::failed) f["error"] = t.error;
        if (!t.incidents.empty()) f["incidents"] = t.incidents;
        frames.push_back(f);
    }
    return {{"source", settings_.source},
            {"evaluation", evaluation()},
            {"software_stage", describer_report(*describer_)},
            {"per_frame", frames}};
}

// Frame i arrives in its task's image buffer; the fault plan learns which frame is there.
void SurfWorkload::deliver(const cv::Mat& frame, const sw::ssa2::Task& task) {
    uint8_t* at = memory_(task.image, uint64_t(frame.cols) * frame.rows);
    for (int y = 0; y < frame.rows; ++y) std::copy_n(frame.ptr(y), frame.cols, at + size_t(y) * frame.cols);
    if (faults_) faults_->frame_arrived(task.image, task.id);
}

void SurfWorkload::reported(const sw::ssa2::Task& task, surf::Keypoints&& keypoints) {
    FrameResult& r = results_[size_t(task.id)];
    r.task = task;
    r.task.candidates = std::vector<uint32_t>();  // released: a long run keeps their count
    r.keypoint_count = keypoints.size();
    r.reported = true;
    ++done_;
    frame_wall_s_.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - software_start_).count());
    if (task.phase == sw::ssa2::Phase::done)
        keypoint_files_.write(size_t(task.id), keypoints);  // a failed frame has no keypoints
    if (kept(size_t(task.id))) r.keypoints = std::move(keypoints);
}

}  // namespace

std::unique_ptr<Workload> make_surf_workload(const Config& config) { return std::make_unique<SurfWorkload>(config); }

void check_surf_inputs(const Config& config) {
    if (run_settings(config).workload != "surf") return;
    check_eval_inputs(config, load_source(config));
}

// Frame 0 at most 640 pixels wide, PNG inline, each keypoint a circle of 2.5 scales with a
// stroke to its orientation (red: dark blob, Laplacian +1; blue: bright blob: surfvp draw's).
std::string SurfWorkload::first_frame_svg() const {
    if (results_.empty() || !results_[0].reported) return "";
    const cv::Mat& frame = source_.first;
    const double f = std::min(1.0, 640.0 / frame.cols);
    cv::Mat shown;
    cv::resize(frame, shown, cv::Size(), f, f, cv::INTER_AREA);
    std::vector<uchar> png;
    media::encode_image(".png", shown, png);
    std::string svg = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"keypoints\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} "
        "{1}\" style=\"max-width:100%;height:auto\">"
        "<image width=\"{0}\" height=\"{1}\" href=\"data:image/png;base64,{2}\"/>",
        shown.cols, shown.rows, YAML::EncodeBase64(png.data(), png.size()));
    for (const surf::Keypoint& k : results_[0].keypoints) {
        const double x = (k.x + 0.5) * f, y = (k.y + 0.5) * f, r = std::max(2.0, 2.5 * k.scale * f);
        const char* c = k.laplacian > 0 ? "#ff0000" : "#0080ff";  // surfvp draw's colours
        svg += fmt::format(
            "<circle class=\"keypoint\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{:.1f}\" fill=\"none\" stroke=\"{}\"/>"
            "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\"/>",
            x, y, r, c, x, y, x + r * std::cos(k.orientation), y - r * std::sin(k.orientation), c);
    }
    return svg +
           fmt::format(
               "<text x=\"6\" y=\"{}\" fill=\"yellow\" font-family=\"sans-serif\">frame 0: {} keypoints</text></svg>",
               shown.rows - 8, results_[0].keypoint_count);
}

surf::Params chip_surf_params(const Config& c) {
    surf::Params p = surf::paper_surf();
    p.octaves = 2;
    p.init_step = 1;
    const SurfWorkloadSettings s = surf_settings(c);
    p.upright = s.upright;
    p.haar = s.haar;
    p.max_offset = s.max_offset;
    p.descriptor = s.descriptor;
    // The chip's software keeps every maximum the FHG marks and it confirms (twins are 0.1 % of
    // its keypoints): its float twin, which calibrates its threshold, keeps them too.
    p.one_per_blob = false;
    return p;
}

std::string threshold_rule_text(const Config& c, const std::string& whose) {
    const SurfWorkloadSettings s = surf_settings(c);
    const uint64_t target = s.target_keypoints;
    if (target == 0) return "surf.threshold";
    const std::string first =
        fmt::format("the {}th strongest response {} on frame 0 (surf.target_keypoints)", target, whose);
    if (!s.track) return first + ", held for every frame";
    const unsigned delay = s.tasks_in_flight;
    return fmt::format(
        "{} for the first {} frames, then each from the keypoint count of the frame {} before it "
        "(surf.threshold_control = track)",
        first, delay, delay);
}

}  // namespace surfvp
