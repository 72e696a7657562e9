// The SURF workload: frames in memory, libSSA2 driving the accelerators, the software stage
// describing the candidates; judged on frame rate against the budget.
#include <algorithm>
#include <filesystem>
#include <map>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <yaml-cpp/binary.h>

#include "platform/address_map.h"
#include "platform/workload/describer.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/hessian_core.h"
#include "platform/soc.h"
#include "sw/eval/distinguishability.h"
#include "sw/eval/homography.h"
#include "sw/eval/keypoint_file.h"
#include "sw/eval/pose_geometry.h"
#include "sw/eval/repeatability.h"
#include "sw/eval/sequence.h"
#include "sw/libssa2/libssa2.h"
#include "sw/surf/image_io.h"
#include "sw/surf/surf.h"
#include "platform/report/report_html.h"
#include "platform/workload/workload.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;

constexpr uint64_t kPage = 4096;
constexpr uint32_t kOutsideMemory = 0xF000'0000;  // a dma_outside_memory fault's buffer: no DDR there
uint64_t round_up(uint64_t v) { return (v + kPage - 1) / kPage * kPage; }

// Where a run's buffers are in memory: the frames, then one set of integral image,
// determinant and descriptor buffers per task in flight. Throws ConfigError when they do not
// fit memory.size.
struct Layout {
    uint64_t frame_bytes, integral_bytes, det_bytes, slot_bytes, frames_base, slots_base;
};

Layout layout_for(const Config& c, size_t frames, int width, int height) {
    Layout l{};
    l.frame_bytes = round_up(uint64_t(width) * height);
    l.integral_bytes = round_up(uint64_t(width) * height * 4);
    l.det_bytes = round_up(uint64_t((width + 1) / 2) * ((height + 1) / 2) *
                           fhg_regs::record_bytes(fhg_regs::det_bytes_for(c.bits("fhg.det_bits"))));
    l.slot_bytes = l.integral_bytes + l.det_bytes + round_up(uint64_t(sw::ssa2::kRecordRing) * sw::ssa2::kRecordSlot);
    l.frames_base = 0x0010'0000;
    l.slots_base = l.frames_base + frames * l.frame_bytes;
    const uint64_t end = l.slots_base + c.count("surf.tasks_in_flight") * l.slot_bytes;
    if (end > c.bytes("memory.size").n)
        throw ConfigError(fmt::format("{}: {} frames of {}x{} and {} buffer sets need {} of memory, memory.size is {}",
                                      c.where("memory.size"), frames, width, height, c.count("surf.tasks_in_flight"),
                                      format_bytes(Bytes{end}), format_bytes(c.bytes("memory.size"))));
    return l;
}

// The frames surf.source names, as the chip takes them (grey, resized to surf.width x
// surf.height when both are set), and each frame's file when it has one. Every problem is bad
// input named at surf.source's origin, found before anything is built.
struct SourceFrames {
    std::vector<cv::Mat> images;
    std::vector<fs::path> files;  // empty for a video or one repeated image
    cv::Size original;            // frame 0 before resizing
};

// Frames the chip can take: at least the filters' minimum (the float reference that
// calibrates the threshold runs on frame 0), at most what the IIG and FHG accept.
void check_frame_size(const Config& c, const SourceFrames& f) {
    const cv::Size size = f.images[0].size();
    const bool resized = size != f.original;
    const std::string where = resized ? c.where("surf.width") : c.where("surf.source");
    const std::string what = resized ? fmt::format("frames resized to {}x{} (surf.width x surf.height)", size.width, size.height)
                                     : fmt::format("frames of {}x{}", size.width, size.height);
    surf::Params reference;
    reference.octaves = 2;
    reference.init_step = 1;
    const int side = surf::minimum_image_side(reference);
    if (size.width < side || size.height < side)
        throw ConfigError(fmt::format("{}: {} are too small: the first octave's largest filter needs at least {}x{}", where,
                                      what, side, side));
    for (const char* block : {"iig", "fhg"})
        for (const auto& [key, pixels] : {std::pair{fmt::format("{}.max_width", block), size.width},
                                          std::pair{fmt::format("{}.max_height", block), size.height}})
            if (uint64_t(pixels) > c.count(key))
                throw ConfigError(fmt::format("{}: {} are larger than the chip takes: {} is {} (from {})", where, what, key,
                                              c.count(key), c.source_of(key)));
}

SourceFrames read_frames(const Config& c) {
    const std::string source = c.text("surf.source");
    const std::string where = c.where("surf.source");
    const size_t count = c.count("surf.frames");
    std::error_code ec;
    const fs::file_status status = fs::status(source, ec);
    if (!fs::exists(status)) throw ConfigError(fmt::format("{}: {}: no such file or folder", where, source));
    // A FIFO or a device would be read until it ends, which may be never.
    if (!fs::is_regular_file(status) && !fs::is_directory(status))
        throw ConfigError(fmt::format("{}: {}: not a regular file or a folder", where, source));
    // More frames than the source has would be fewer frames than asked, silently.
    auto too_few = [&](size_t has) {
        return ConfigError(fmt::format("{}: surf.frames is {} (from {}), but {} has only {}", where, count,
                                       c.source_of("surf.frames"), source, has));
    };
    SourceFrames out;
    try {
        surf::QuietDecoding quiet;
        if (fs::is_regular_file(status) && (eval::is_image_file(source) || !cv::imread(source, cv::IMREAD_GRAYSCALE).empty())) {
            out.images.assign(count, surf::load_gray(source));  // one image, repeated
        } else {
            eval::Sequence sequence = eval::open_sequence(source, count);
            if (sequence.frames.size() < count) throw too_few(sequence.frames.size());  // before decoding them all
            eval::SequenceReader reader(std::move(sequence));
            for (cv::Mat frame; out.images.size() < count && reader.next(frame);) {
                // Host memory stays bounded: what the frames need in the chip's memory is
                // checked on the first, before the others are decoded.
                if (out.images.empty())
                    layout_for(c, count, c.count("surf.width") && c.count("surf.height") ? int(c.count("surf.width")) : frame.cols,
                               c.count("surf.width") && c.count("surf.height") ? int(c.count("surf.height")) : frame.rows);
                out.images.push_back(frame.clone());
                const fs::path& file = reader.sequence().frames[out.images.size() - 1].image;
                if (!file.empty()) out.files.push_back(file);
            }
        }
    } catch (const ConfigError&) {
        throw;
    } catch (const std::exception& e) {
        throw ConfigError(fmt::format("{}: {}", where, e.what()));
    }
    if (out.images.size() < count) throw too_few(out.images.size());
    auto name = [&](size_t i) { return i < out.files.size() ? out.files[i].string() : fmt::format("{} frame {}", source, i); };
    out.original = out.images[0].size();
    const bool resizing = c.count("surf.width") && c.count("surf.height");
    for (size_t i = 1; i < out.images.size(); ++i)
        if (!resizing && out.images[i].size() != out.original)
            throw ConfigError(fmt::format("{}: frames differ in size: {} is {}x{}, {} is {}x{}; set surf.width and surf.height "
                                          "to resize them alike",
                                          where, name(0), out.original.width, out.original.height, name(i),
                                          out.images[i].cols, out.images[i].rows));
    // Frames that share their pixels (one image, repeated) share the resized pixels too: one
    // resize, not one copy per frame.
    const int w = int(c.count("surf.width")), h = int(c.count("surf.height"));
    const uchar* shared = nullptr;
    cv::Mat resized;
    for (cv::Mat& f : out.images)
        if (w && h && f.size() != cv::Size(w, h)) {
            if (f.data != shared) {
                shared = f.data;
                resized = cv::Mat();
                cv::resize(f, resized, cv::Size(w, h), 0, 0, cv::INTER_AREA);
            }
            f = resized;
        }
    check_frame_size(c, out);
    return out;
}

// Frames, and frame 0's ranked responses for the calibration, are read once per process and
// source: the verdict's re-simulations are forked from one process and inherit them.
std::string source_key(const Config& c) {
    return fmt::format("{}|{}x{}", c.text("surf.source"), c.count("surf.width"), c.count("surf.height"));
}

const SourceFrames& load_source(const Config& c) {
    static std::map<std::string, SourceFrames> cache;
    const std::string key = fmt::format("{}|{}", source_key(c), c.count("surf.frames"));
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, read_frames(c)).first;
    return it->second;
}

const std::vector<cv::Mat>& load_frames(const Config& c) { return load_source(c).images; }

// The evaluation's geometry, read before anything is built: a homography from frame 0 to
// frame 1 at the frames' own size, and camera poses that belong to the very frames the source
// gives, one each.
void check_eval_inputs(const Config& c, const SourceFrames& frames) {
    const std::string homography = c.text("eval.homography");
    if (!homography.empty()) {
        try {
            eval::read_homography_file(homography);
        } catch (const std::exception& e) {
            throw ConfigError(fmt::format("{}: {}", c.where("eval.homography"), e.what()));
        }
        if (frames.images[0].size() != frames.original)
            throw ConfigError(fmt::format("{}: the homography maps frame 0 to frame 1 at their own size ({}x{}), but "
                                          "surf.width x surf.height (from {}) resize them to {}x{}; set both to 0",
                                          c.where("eval.homography"), frames.original.width, frames.original.height,
                                          c.source_of("surf.width"), frames.images[0].cols, frames.images[0].rows));
    }
    const std::string poses = c.text("eval.poses");
    if (poses.empty()) return;
    std::vector<eval::PosedFrame> posed;
    try {
        posed = eval::list_posed_frames(poses);
    } catch (const std::exception& e) {
        throw ConfigError(fmt::format("{}: {}", c.where("eval.poses"), e.what()));
    }
    if (frames.files.size() != frames.images.size())
        throw ConfigError(fmt::format("{}: poses belong to image files, but surf.source {} (from {}) is one image or a video",
                                      c.where("eval.poses"), c.text("surf.source"), c.source_of("surf.source")));
    if (posed.size() < frames.images.size())
        throw ConfigError(fmt::format("{}: {} poses for {} frames (surf.frames from {})", c.where("eval.poses"), posed.size(),
                                      frames.images.size(), c.source_of("surf.frames")));
    // The evaluation's pairs (gaps 1 and 2, evaluation() below) need two distinct camera centres.
    for (size_t i = 0; i < frames.images.size(); ++i)
        for (size_t j : {i + 1, i + 2})
            if (j < frames.images.size()) try {
                    eval::fundamental_from_poses(eval::kCastleIntrinsics, posed[i].c_m_o, posed[j].c_m_o);
                } catch (const std::invalid_argument& e) {
                    throw ConfigError(fmt::format("{}: frames {} and {} ({} and {}): {}", c.where("eval.poses"), i, j,
                                                  posed[i].pose_file.string(), posed[j].pose_file.string(), e.what()));
                }
    for (size_t i = 0; i < frames.files.size(); ++i) {
        std::error_code ec;
        if (!fs::equivalent(frames.files[i], posed[i].image, ec))
            throw ConfigError(fmt::format("{}: frame {} is {}, but pose {} ({}) belongs to {}", c.where("eval.poses"), i,
                                          frames.files[i].string(), i, posed[i].pose_file.filename().string(),
                                          posed[i].image.string()));
    }
}

// The float reference on frame 0, limited to the chip's two octaves at step 1.
float calibrate(const Config& c, const cv::Mat& frame) {
    if (c.count("surf.target_keypoints") == 0) return float(c.real("surf.threshold"));
    static std::map<std::string, std::vector<float>> ranked;
    const std::string key = fmt::format("{}|{}", source_key(c), c.choice("surf.upright"));
    auto it = ranked.find(key);
    if (it == ranked.end()) {
        surf::Params p;
        p.octaves = 2;
        p.init_step = 1;
        p.upright = c.choice("surf.upright") == "on";
        it = ranked.emplace(key, surf::ranked_responses(frame, p)).first;
    }
    return surf::threshold_for_rank(it->second, int(c.count("surf.target_keypoints")));
}

struct FrameResult {
    surf::Keypoints keypoints;
    sw::ssa2::Task task;
    bool reported = false;
};

class SurfWorkload : public Workload {
public:
    explicit SurfWorkload(const Config& c)
        : config_(c), frames_(load_frames(c)), threshold_(calibrate(c, frames_[0])),
          describer_(make_describer(c, threshold_)), results_(frames_.size()) {
        width_ = frames_[0].cols;
        height_ = frames_[0].rows;
        layout_ = layout_for(c, frames_.size(), width_, height_);
        const fhg::HessianCore core(fhg_params(c).precision);
        driver_.intc_base = map::intc.base;
        for (unsigned k = 0; k < c.count("soc.accelerators"); ++k)
            driver_.accelerators.push_back({map::iig_base(k), map::fhg_base(k), map::irq::iig(k), map::irq::fhg(k)});
        for (uint64_t set = 0, at = layout_.slots_base; set < c.count("surf.tasks_in_flight"); ++set, at += layout_.slot_bytes)
            driver_.buffers.push_back({uint32_t(at), uint32_t(at + layout_.integral_bytes),
                                       uint32_t(at + layout_.integral_bytes + layout_.det_bytes)});
        driver_.fifo_irq_level = uint32_t(c.count("surf.fifo_irq_level"));
        driver_.threshold = core.from_float(threshold_);
        driver_.watchdog_ps = c.duration("surf.watchdog").ps;
        driver_.spurious_irq_limit = unsigned(c.count("surf.spurious_irq_limit"));
        budget_fps_ = c.real("budget.fps");
        // A frame rate needs one whole round of the pairs after the first frame.
        if (budget_fps_ > 0 && frames_.size() <= c.count("soc.accelerators"))
            throw ConfigError(fmt::format("surf.frames: {} frames cannot give a frame rate with {} accelerator pair(s): "
                                          "the steady-state rate needs {}; set more frames or budget.fps = 0",
                                          frames_.size(), c.count("soc.accelerators"), c.count("soc.accelerators") + 1));
        cpu_hz_ = c.frequency("cpu.clock").hz;
    }

    void preload(const Backdoor& memory) override {
        for (size_t i = 0; i < frames_.size(); ++i) {
            uint8_t* at = memory(frame_address(i), uint64_t(width_) * height_);
            for (int y = 0; y < height_; ++y) std::copy_n(frames_[i].ptr(y), width_, at + size_t(y) * width_);
        }
    }

    void inject(FaultPlan& faults) override {
        faults_ = &faults;
        std::vector<uint32_t> images;
        for (size_t i = 0; i < frames_.size(); ++i) images.push_back(frame_address(i));
        faults.set_frame_images(std::move(images));
    }

    Ppc440::Software software() override {
        return [this](sw::Hal& hal) {
            std::vector<sw::ssa2::Task> tasks(frames_.size());
            for (size_t i = 0; i < tasks.size(); ++i) {
                tasks[i].image = frame_address(i);
                tasks[i].width = width_;
                tasks[i].height = height_;
            }
            if (faults_) give_buffers_outside_memory(tasks, hal.time_ps());
            sw::ssa2::Driver driver(hal, driver_, *describer_);
            driver.run(tasks, [this](const sw::ssa2::Task& task, surf::Keypoints&& keypoints) {
                FrameResult& r = results_[size_t(task.id)];
                r.task = task;
                r.keypoints = std::move(keypoints);
                r.reported = true;
                ++done_;
            });
            accelerator_time_ = driver.accelerator_time();
            recovery_ = driver.recovery();
        };
    }

    Progress progress() const override { return {done_, frames_.size(), "frames"}; }

    std::vector<Check> checks() const override {
        std::vector<Check> checks;
        std::vector<std::string> failures;
        size_t lost_to_faults = 0, done = 0;
        for (const FrameResult& r : results_) {
            done += r.task.phase == sw::ssa2::Phase::done;
            if (r.task.phase != sw::ssa2::Phase::failed) continue;
            if (struck_by_fault(r.task.id)) ++lost_to_faults;
            else failures.push_back(fmt::format("frame {}: {}", r.task.id, r.task.error));
        }
        const std::string lost = lost_to_faults ? fmt::format("; {} lost to injected faults", lost_to_faults) : "";
        checks.push_back({"every frame processed", failures.empty() && done + lost_to_faults == frames_.size(),
                          failures.empty() ? fmt::format("{} of {} frames{}", done, frames_.size(), lost)
                                           : fmt::format("{}", fmt::join(failures, "; "))});
        if (faults_) checks.push_back(fault_check());
        if (budget_fps_ > 0) {
            const double fps = throughput();
            checks.push_back({"frame-rate budget", fps >= budget_fps_,
                              fmt::format("{:.2f} frames/s against {:.2f}", fps, budget_fps_)});
        }
        return checks;
    }

    nlohmann::ordered_json summary() const override;
    nlohmann::ordered_json report() const override;
    std::vector<std::string> write_files(const std::string& dir) const override;
    std::string first_frame_svg() const override;

    // Each frame's hardware phases on its accelerator's track and its descriptors on the
    // CPU's: frames overlapping across the chip.
    void trace(Tracer& tracer) const override {
        if (!tracer.perfetto_on()) return;
        std::vector<int> hardware;
        for (size_t k = 0; k < driver_.accelerators.size(); ++k)
            hardware.push_back(tracer.track("frames", fmt::format("accelerator {} (integral + determinants)", k)));
        const int descriptors = tracer.track("frames", "cpu (descriptors)");
        auto at = [](uint64_t ps) { return sc_core::sc_time(double(ps), sc_core::SC_PS); };
        for (const FrameResult& r : results_) {
            const auto& t = r.task;
            if (!r.reported || t.t_determinants == 0) continue;
            const std::string name = fmt::format("frame {}{}", t.id, t.phase == sw::ssa2::Phase::failed ? " (failed)" : "");
            tracer.slice(hardware[size_t(t.id) % hardware.size()], name, at(t.t_start), at(t.t_determinants));
            if (t.phase == sw::ssa2::Phase::done) tracer.slice(descriptors, name, at(t.t_determinants), at(t.t_done));
        }
    }

private:
    uint32_t frame_address(size_t i) const { return uint32_t(layout_.frames_base + i * layout_.frame_bytes); }


    double throughput() const;
    nlohmann::ordered_json evaluation() const;
    void give_buffers_outside_memory(std::vector<sw::ssa2::Task>& tasks, uint64_t now_ps) const;
    bool struck_by_fault(int frame) const;
    bool detected(const Fault& fault) const;
    bool recovered(const Fault& fault) const;
    Check fault_check() const;
    nlohmann::ordered_json fault_report() const;
    // How the threshold was chosen (calibrate() above).
    std::string threshold_rule() const {
        const int64_t target = config_.count("surf.target_keypoints");
        if (target == 0) return "surf.threshold";
        return fmt::format("the {}th strongest response of the float reference on frame 0 (2 octaves, step 1; "
                           "surf.target_keypoints = {}), held for every frame",
                           target, target);
    }

    const Config& config_;
    std::vector<cv::Mat> frames_;
    float threshold_;
    std::unique_ptr<sw::ssa2::Describer> describer_;
    std::vector<FrameResult> results_;
    sw::ssa2::DriverConfig driver_;
    int width_ = 0, height_ = 0;
    Layout layout_{};
    uint64_t done_ = 0;
    FaultPlan* faults_ = nullptr;
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
        if (!f.fired) missed.push_back(f.describe() + " never struck (" + f.origin + ")");
        else if (!detected(f)) missed.push_back(f.describe() + " went undetected");
    }
    const size_t n = faults_->faults().size();
    return {"every injected fault detected", missed.empty(),
            missed.empty() ? fmt::format("{} of {} faults struck and were detected", n, n) : fmt::format("{}", fmt::join(missed, "; "))};
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
                               : t.incidents.empty()               ? std::string("frame done, nothing noticed")
                                                                   : "frame done: " + fmt::format("{}", fmt::join(t.incidents, "; "));
            }
        }
        list.push_back(j);
    }
    for (const FrameResult& r : results_) lost += r.task.phase == sw::ssa2::Phase::failed;
    return {{"given", faults_->faults().size()}, {"injected", injected}, {"detected", detected_n},
            {"tasks_lost", lost}, {"recovered", recovered_n},
            {"driver", {{"watchdog_expiries", recovery_.watchdog_expiries},
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
        keypoints += double(r.keypoints.size());
        cycles += double(t.descriptor_cycles);
        min_kp = std::min(min_kp, r.keypoints.size());
        max_kp = std::max(max_kp, r.keypoints.size());
        ++n;
    }
    const double per = n ? 1.0 / double(n) : 0;
    const double fps = throughput();
    nlohmann::ordered_json budget = nullptr;
    if (budget_fps_ > 0) budget = {{"fps", budget_fps_}, {"met", fps >= budget_fps_}};
    nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
    for (const auto& a : accelerator_time_)
        pairs.push_back({{"working_s", a.working_ps * 1e-12}, {"waiting_for_buffers_s", a.waiting_for_buffers_ps * 1e-12},
                         {"idle_s", a.idle_ps * 1e-12}});
    nlohmann::ordered_json out = {{"image", {{"width", width_}, {"height", height_}}},
            {"frames", frames_.size()},
            {"frames_done", n},
            {"throughput_fps", fps},
            {"latency_ms", latency * per * 1e-9},
            {"keypoints_per_frame", keypoints * per},
            {"keypoints_per_frame_range", {n ? min_kp : 0, max_kp}},
            {"threshold", threshold_},
            {"threshold_rule", threshold_rule()},
            {"budget", budget},
            {"phases_ms", {{"integral_image", integral * per * 1e-9},
                           {"determinants", determinants * per * 1e-9},
                           {"descriptors", describe * per * 1e-9}}},
            {"software_time_per_keypoint_us", keypoints > 0 ? cycles / keypoints / cpu_hz_ * 1e6 : 0.0},
            {"software_cycles_per_keypoint", keypoints > 0 ? cycles / keypoints : 0.0},
            {"accelerator_pairs", pairs}};
    if (faults_) out["faults"] = fault_report();
    return out;
}

nlohmann::ordered_json SurfWorkload::report() const {
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    for (const FrameResult& r : results_) {
        const auto& t = r.task;
        nlohmann::ordered_json f = {{"frame", t.id}, {"candidates", t.candidates.size()}, {"keypoints", r.keypoints.size()},
                                    {"start_ms", t.t_start * 1e-9}, {"integral_done_ms", t.t_integral * 1e-9},
                                    {"determinants_done_ms", t.t_determinants * 1e-9}, {"done_ms", t.t_done * 1e-9},
                                    {"descriptor_cycles", t.descriptor_cycles}};
        if (t.phase == sw::ssa2::Phase::failed) f["error"] = t.error;
        if (!t.incidents.empty()) f["incidents"] = t.incidents;
        frames.push_back(f);
    }
    return {{"source", config_.text("surf.source")}, {"evaluation", evaluation()},
            {"software_stage", describer_report(*describer_)}, {"per_frame", frames}};
}

// Feature quality on the chip's own keypoints, when the scenario gives the geometry.
nlohmann::ordered_json SurfWorkload::evaluation() const {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    if (done_ != frames_.size()) return out;
    const std::string homography = config_.text("eval.homography");
    if (!homography.empty() && results_.size() >= 2) {
        const Eigen::Matrix3d h = eval::read_homography_file(homography);
        const auto rep = eval::repeatability(results_[0].keypoints, results_[1].keypoints, h, frames_[0].size(),
                                             frames_[1].size());
        const auto prec = eval::matching_precision(results_[0].keypoints, results_[1].keypoints, h);
        out["homography"] = {{"repeatability", rep.repeatability}, {"correspondences", rep.correspondences},
                             {"precision", prec.precision}, {"candidates", prec.candidates}};
    }
    const std::string poses = config_.text("eval.poses");
    if (!poses.empty() && results_.size() >= 2) {
        std::vector<surf::Keypoints> all;
        for (const FrameResult& r : results_) all.push_back(r.keypoints);
        const auto posed = eval::list_posed_frames(poses);
        const eval::CameraIntrinsics k = eval::kCastleIntrinsics;
        for (size_t gap : {size_t(1), size_t(2)}) {
            const auto ransac = eval::sequence_distinguishability(all, gap);
            const auto truth = eval::sequence_distinguishability(all, gap, [&](size_t i, size_t j) {
                return eval::fundamental_from_poses(k, posed.at(i).c_m_o, posed.at(j).c_m_o);
            });
            out[fmt::format("distinguishability_gap{}", gap)] = {{"ransac", ransac.mean}, {"ground_truth", truth.mean},
                                                                  {"pairs", ransac.pairs.size()}};
        }
    }
    return out;
}

std::vector<std::string> SurfWorkload::write_files(const std::string& dir) const {
    const fs::path folder = fs::path(dir) / "keypoints";
    fs::create_directories(folder);
    std::vector<std::string> written;
    for (const FrameResult& r : results_) {
        if (!r.reported || r.task.phase != sw::ssa2::Phase::done) continue;  // a failed frame has no keypoints
        const fs::path file = folder / fmt::format("frame_{:04}.surf", r.task.id);
        eval::write_keypoint_file(file, r.keypoints);
        written.push_back(fs::relative(file, dir).string());
    }
    return written;
}

}  // namespace

std::unique_ptr<Workload> make_surf_workload(const Config& config) { return std::make_unique<SurfWorkload>(config); }

void check_surf_inputs(const Config& config) {
    if (config.choice("run.workload") != "surf") return;
    check_eval_inputs(config, load_source(config));
}

// Frame 0 at most 640 pixels wide, PNG inline, each keypoint a circle of 2.5 scales with a
// stroke to its orientation (green: dark blob, Laplacian +1; red: bright blob).
std::string SurfWorkload::first_frame_svg() const {
    if (results_.empty() || !results_[0].reported) return "";
    const cv::Mat& frame = frames_[0];
    const double f = std::min(1.0, 640.0 / frame.cols);
    cv::Mat shown;
    cv::resize(frame, shown, cv::Size(), f, f, cv::INTER_AREA);
    std::vector<uchar> png;
    cv::imencode(".png", shown, png);
    std::string svg = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"keypoints\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">"
        "<image width=\"{0}\" height=\"{1}\" href=\"data:image/png;base64,{2}\"/>",
        shown.cols, shown.rows, YAML::EncodeBase64(png.data(), png.size()));
    for (const surf::Keypoint& k : results_[0].keypoints) {
        const double x = (k.x + 0.5) * f, y = (k.y + 0.5) * f, r = std::max(2.0, 2.5 * k.scale * f);
        const char* c = k.laplacian > 0 ? "#00e000" : "#ff3030";
        svg += fmt::format("<circle class=\"keypoint\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{:.1f}\" fill=\"none\" stroke=\"{}\"/>"
                           "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\"/>",
                           x, y, r, c, x, y, x + r * std::cos(k.orientation), y - r * std::sin(k.orientation), c);
    }
    return svg + fmt::format("<text x=\"6\" y=\"{}\" fill=\"yellow\" font-family=\"sans-serif\">frame 0: {} keypoints</text></svg>",
                             shown.rows - 8, results_[0].keypoints.size());
}

}  // namespace surfvp
