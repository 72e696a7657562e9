// The SURF workload: frames in memory, libSSA2 driving the accelerators, the software stage
// describing the candidates; judged on frame rate against the budget.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>  // cv::IMREAD_GRAYSCALE
#include <opencv2/imgproc.hpp>
#include <yaml-cpp/binary.h>

#include "models/host/worker.h"
#include "models/common/zeroed_memory.h"
#include "platform/address_map.h"
#include "platform/workload/describer.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/hessian_core.h"
#include "platform/scenario/block_params.h"
#include "sw/eval/distinguishability.h"
#include "sw/eval/homography.h"
#include "sw/eval/keypoint_file.h"
#include "sw/eval/pose_geometry.h"
#include "sw/eval/repeatability.h"
#include "sw/eval/sequence.h"
#include "sw/libssa2/libssa2.h"
#include "sw/media/media.h"
#include "sw/surf/image_io.h"
#include "sw/surf/surf.h"
#include "models/host/xml_text.h"
#include "platform/workload/workload.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;

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
    const uint32_t det = fhg_regs::det_bytes_for(c.bits("fhg.det_bits"));
    l.det_bytes = round_up(fhg_regs::buffer_bytes(uint32_t(width), uint32_t(height), det));
    l.slot_bytes = l.image_bytes + l.integral_bytes + l.det_bytes +
                   round_up(uint64_t(sw::ssa2::kRecordRing) * sw::ssa2::kRecordSlot);
    l.slots_base = 0x0010'0000;
    const uint64_t sets = c.count("surf.tasks_in_flight");
    const uint64_t end = l.slots_base + sets * l.slot_bytes;
    if (end > c.bytes("memory.size").n)
        throw ConfigError(
            fmt::format("{}: {} buffer sets (surf.tasks_in_flight, from {}) for frames of {}x{} need {} of "
                        "memory, memory.size is {}",
                        c.where("memory.size"), sets, c.source_of("surf.tasks_in_flight"), width, height,
                        format_bytes(Bytes{end}), format_bytes(c.bytes("memory.size"))));
    return l;
}

// The frames surf.source names, as the chip takes them (grey, resized to surf.width x
// surf.height when both are set). Every frame is decoded and checked once before anything is
// built, and none is kept but frame 0 (the threshold's calibration, the report's picture): a
// run decodes each again as it arrives (FrameStream), so host memory does not grow with the
// frames either.
struct SourceFrames {
    size_t count = 0;
    bool repeated = false;        // one image, every frame
    cv::Mat first;                // frame 0 as the chip takes it
    std::vector<fs::path> files;  // each frame's file; empty for a video or one repeated image
    cv::Size original;            // frame 0 before resizing
    std::vector<cv::Size> sizes;  // each frame's size as the chip takes it (images of a folder or list may differ)
    cv::Size largest() const {
        cv::Size most;
        for (const cv::Size& s : sizes) most = cv::Size(std::max(most.width, s.width), std::max(most.height, s.height));
        return most;
    }
};

// A frame's size as the chip takes it: surf.width x surf.height when both are set.
cv::Size chip_size(const Config& c, cv::Size frame) {
    const int w = int(c.count("surf.width")), h = int(c.count("surf.height"));
    return w && h ? cv::Size(w, h) : frame;
}

cv::Mat as_the_chip_takes(const Config& c, const cv::Mat& frame) {
    const cv::Size size = chip_size(c, frame.size());
    if (frame.size() == size) return frame;
    cv::Mat resized;
    cv::resize(frame, resized, size, 0, 0, cv::INTER_AREA);
    return resized;
}

// Frames the chip can take: at least the filters' minimum (the float reference that
// calibrates the threshold runs on frame 0), at most what the IIG and FHG accept.
void check_frame_size(const Config& c, const SourceFrames& f) {
    const int side = surf::minimum_image_side(chip_surf_params(c));
    const bool resized = f.first.size() != f.original;
    const bool alike = std::all_of(f.sizes.begin(), f.sizes.end(), [&](const cv::Size& s) { return s == f.sizes[0]; });
    const std::string where = resized ? c.where("surf.width") : c.where("surf.source");
    for (size_t i = 0; i < f.sizes.size(); ++i) {
        const cv::Size size = f.sizes[i];
        if (i > 0 && size == f.sizes[i - 1]) continue;
        const std::string what =
            resized ? fmt::format("frames resized to {}x{} (surf.width x surf.height) are", size.width, size.height)
            : alike ? fmt::format("frames of {}x{} are", size.width, size.height)
                    : fmt::format("frame {} ({}) of {}x{} is", i, f.files[i].string(), size.width, size.height);
        if (size.width < side || size.height < side)
            throw ConfigError(fmt::format("{}: {} too small: the first octave's largest filter needs at least {}x{}",
                                          where, what, side, side));
        for (const char* block : {"iig", "fhg"})
            for (const auto& [key, pixels] : {std::pair{fmt::format("{}.max_width", block), size.width},
                                              std::pair{fmt::format("{}.max_height", block), size.height}})
                if (uint64_t(pixels) > c.count(key))
                    throw ConfigError(fmt::format("{}: {} larger than the chip takes: {} is {} (from {})", where, what,
                                                  key, c.count(key), c.source_of(key)));
    }
}

// A sequence's frames (a folder, a list or a video), decoded in order.
eval::SequenceReader open_frames(const Config& c) {
    return eval::SequenceReader(eval::open_sequence(c.text("surf.source"), c.count("surf.frames")));
}

// Every frame of a sequence decoded once: its file, and its size against frame 0's.
void read_sequence(const Config& c, SourceFrames& out) {
    const std::string source = c.text("surf.source");
    auto too_few = [&](size_t has) {
        return ConfigError(fmt::format("{}: surf.frames is {} (from {}), but {} has only {}", c.where("surf.source"),
                                       out.count, c.source_of("surf.frames"), source, has));
    };
    eval::SequenceReader reader = open_frames(c);
    if (reader.sequence().frames.size() < out.count) throw too_few(reader.sequence().frames.size());  // before decoding
    size_t n = 0;
    for (cv::Mat frame; n < out.count && reader.next(frame); ++n) {
        const fs::path& file = reader.sequence().frames[n].image;
        if (!file.empty()) out.files.push_back(file);
        if (n == 0) {
            out.first = frame.clone();
            out.original = frame.size();
        }
        out.sizes.push_back(chip_size(c, frame.size()));
    }
    if (n < out.count) throw too_few(n);
}

SourceFrames read_frames(const Config& c) {
    const std::string source = c.text("surf.source");
    const std::string where = c.where("surf.source");
    std::error_code ec;
    const fs::file_status status = fs::status(source, ec);
    if (!fs::exists(status)) throw ConfigError(fmt::format("{}: {}: no such file or folder", where, source));
    // A FIFO or a device would be read until it ends, which may be never.
    if (!fs::is_regular_file(status) && !fs::is_directory(status))
        throw ConfigError(fmt::format("{}: {}: not a regular file or a folder", where, source));
    SourceFrames out;
    out.count = c.count("surf.frames");
    try {
        surf::QuietDecoding quiet;
        if (fs::is_regular_file(status) &&
            (eval::is_image_file(source) || !media::read_image(source, cv::IMREAD_GRAYSCALE).empty())) {
            out.repeated = true;
            out.first = surf::load_gray(source, chip_surf_params(c));
            out.original = out.first.size();
            out.sizes.assign(out.count, chip_size(c, out.first.size()));
        } else {
            read_sequence(c, out);
        }
    } catch (const ConfigError&) {
        throw;
    } catch (const OutOfMemory&) {  // the machine's, not the source's fault
        throw;
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(fmt::format("reading the frames of {}", where));
    } catch (const cv::Exception& e) {
        if (e.code == cv::Error::StsNoMem) throw OutOfMemory(fmt::format("reading the frames of {}: {}", where, e.err));
        throw ConfigError(fmt::format("{}: {}", where, e.what()));
    } catch (const std::exception& e) {
        throw ConfigError(fmt::format("{}: {}", where, e.what()));
    }
    out.first = as_the_chip_takes(c, out.first);
    check_frame_size(c, out);
    return out;
}

// The frames of a run as they arrive, in order; one decoded at a time.
class FrameStream {
public:
    FrameStream(const Config& c, const SourceFrames& source) : config_(c), source_(source) {}

    // Frame i as the chip takes it: the next after the one before (a frame before it starts
    // the sequence again).
    const cv::Mat& frame(size_t i) {
        if (source_.repeated || i == 0) return source_.first;
        if (!reader_ || i < reader_->position()) reader_.emplace(open_frames(config_));
        surf::QuietDecoding quiet;
        cv::Mat decoded;
        while (reader_->position() <= i)
            if (!reader_->next(decoded))
                throw std::runtime_error(
                    fmt::format("{}: frame {} can no longer be read", config_.text("surf.source"), i));
        current_ = as_the_chip_takes(config_, decoded);
        return current_;
    }

private:
    const Config& config_;
    const SourceFrames& source_;
    std::optional<eval::SequenceReader> reader_;
    cv::Mat current_;
};

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

// Pairs (i, i + gap) the evaluation measures: consecutive frames and eval.gap.
std::vector<size_t> evaluated_gaps(const Config& c) {
    std::vector<size_t> gaps{1};
    if (c.count("eval.gap") > 1) gaps.push_back(c.count("eval.gap"));
    return gaps;
}

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
        if (frames.first.size() != frames.original)
            throw ConfigError(
                fmt::format("{}: the homography maps frame 0 to frame 1 at their own size ({}x{}), but "
                            "surf.width x surf.height (from {}) resize them to {}x{}; set both to 0",
                            c.where("eval.homography"), frames.original.width, frames.original.height,
                            c.source_of("surf.width"), frames.first.cols, frames.first.rows));
    }
    const std::string poses = c.text("eval.poses");
    if (poses.empty()) return;
    std::vector<eval::PosedFrame> posed;
    try {
        posed = eval::list_posed_frames(poses);
    } catch (const std::exception& e) {
        throw ConfigError(fmt::format("{}: {}", c.where("eval.poses"), e.what()));
    }
    if (frames.files.size() != frames.count)
        throw ConfigError(
            fmt::format("{}: poses belong to image files, but surf.source {} (from {}) is one image or a video",
                        c.where("eval.poses"), c.text("surf.source"), c.source_of("surf.source")));
    if (posed.size() < frames.count)
        throw ConfigError(fmt::format("{}: {} poses for {} frames (surf.frames from {})", c.where("eval.poses"),
                                      posed.size(), frames.count, c.source_of("surf.frames")));
    // The evaluation's pairs (evaluation() below) need two distinct camera centres.
    for (size_t i = 0; i < frames.count; ++i)
        for (size_t gap : evaluated_gaps(c)) {
            const size_t j = i + gap;
            if (j < frames.count) try {
                    eval::fundamental_from_poses(eval::kCastleIntrinsics, posed[i].c_m_o, posed[j].c_m_o);
                } catch (const std::invalid_argument& e) {
                    throw ConfigError(fmt::format("{}: frames {} and {} ({} and {}): {}", c.where("eval.poses"), i, j,
                                                  posed[i].pose_file.string(), posed[j].pose_file.string(), e.what()));
                }
        }
    for (size_t i = 0; i < frames.files.size(); ++i) {
        std::error_code ec;
        if (!fs::equivalent(frames.files[i], posed[i].image, ec))
            throw ConfigError(fmt::format("{}: frame {} is {}, but pose {} ({}) belongs to {}", c.where("eval.poses"),
                                          i, frames.files[i].string(), i, posed[i].pose_file.filename().string(),
                                          posed[i].image.string()));
    }
}

// The float reference on frame 0, limited to the chip's two octaves at step 1: the threshold,
// and how many maxima frame 0 has (fewer than the target: the threshold is 0, every maximum).
struct Calibration {
    float threshold = 0;
    size_t maxima = 0;
};

Calibration calibrate(const Config& c, const cv::Mat& frame) {
    if (c.count("surf.target_keypoints") == 0) return {float(c.real("surf.threshold")), 0};
    static std::map<std::string, std::vector<float>> ranked;
    const surf::Params p = chip_surf_params(c);
    const std::string key = fmt::format("{}|{}|{}", source_key(c), p.upright, p.max_offset);
    auto it = ranked.find(key);
    if (it == ranked.end()) it = ranked.emplace(key, surf::stored_ranked_responses(frame, p)).first;
    return {surf::threshold_for_rank(it->second, int(c.count("surf.target_keypoints"))), it->second.size()};
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
        for (unsigned k = 0; k < c.count("soc.accelerators"); ++k)
            driver_.accelerators.push_back({map::iig_base(k), map::fhg_base(k), map::irq::iig(k), map::irq::fhg(k)});
        for (uint64_t set = 0, at = layout_.slots_base; set < c.count("surf.tasks_in_flight");
             ++set, at += layout_.slot_bytes)
            driver_.buffers.push_back(
                {uint32_t(at), uint32_t(at + layout_.image_bytes),
                 uint32_t(at + layout_.image_bytes + layout_.integral_bytes),
                 uint32_t(at + layout_.image_bytes + layout_.integral_bytes + layout_.det_bytes)});
        driver_.fifo_irq_level = uint32_t(c.count("surf.fifo_irq_level"));
        driver_.threshold = core.from_float(threshold_);
        if (c.choice("surf.threshold_control") == "track")
            driver_.keypoint_target = uint32_t(c.count("surf.target_keypoints"));
        to_float_ = [core](int32_t t) { return core.to_float(t); };
        driver_.watchdog_ps = c.duration("surf.watchdog").ps;
        driver_.spurious_irq_limit = unsigned(c.count("surf.spurious_irq_limit"));
        budget_fps_ = c.real("budget.fps");
        // A frame rate needs one whole round of the pairs after the first frame.
        if (budget_fps_ > 0 && source_.count <= c.count("soc.accelerators"))
            throw ConfigError(
                fmt::format("surf.frames: {} frames cannot give a frame rate with {} accelerator pair(s): "
                            "the steady-state rate needs {}; set more frames or budget.fps = 0",
                            source_.count, c.count("soc.accelerators"), c.count("soc.accelerators") + 1));
        cpu_hz_ = c.frequency("cpu.clock").hz;
    }

    void attach_memory(const Backdoor& memory) override { memory_ = memory; }
    void inject(FaultPlan& faults) override { faults_ = &faults; }
    void share_worker(Worker* worker) override {
        finish_writes();  // the files handed to the worker before
        // With a second thread (run.parallel) the files get a thread of their own: their system
        // calls block (creating a file alone took ~0.1 ms on ext4 here, two files a frame),
        // which on the shared worker held up the block rows queued behind them.
        writer_ = worker ? std::make_unique<Worker>(std::chrono::microseconds(0)) : nullptr;
        surfvp::share_worker(*describer_, worker);
    }
    void write_into(const std::string& dir) override { out_ = dir; }
    std::vector<std::string> files_written() override;

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
        if (const uint64_t target = config_.count("surf.target_keypoints"); target > 0)
            checks.push_back(
                {"keypoint target reachable", calibration_.maxima > target,
                 calibration_.maxima > target
                     ? fmt::format("frame 0 has {} maxima for surf.target_keypoints = {}", calibration_.maxima, target)
                     : fmt::format("frame 0 has only {} maxima, not more than surf.target_keypoints = {}: the "
                                   "threshold is 0 and every maximum is kept; lower the target",
                                   calibration_.maxima, target)});
        if (budget_fps_ > 0) {
            const double fps = throughput();
            checks.push_back({"frame-rate budget", fps >= budget_fps_,
                              fmt::format("{:.2f} frames/s against {:.2f}", fps, budget_fps_)});
        }
        return checks;
    }

    nlohmann::ordered_json summary() const override;
    nlohmann::ordered_json report() const override;
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
            const std::string name =
                fmt::format("frame {}{}", t.id, t.phase == sw::ssa2::Phase::failed ? " (failed)" : "");
            tracer.slice(hardware[size_t(t.id) % hardware.size()], name, at(t.t_start), at(t.t_determinants));
            if (t.phase == sw::ssa2::Phase::done) tracer.slice(descriptors, name, at(t.t_determinants), at(t.t_done));
        }
    }

private:
    void deliver(const cv::Mat& frame, const sw::ssa2::Task& task);
    void reported(const sw::ssa2::Task& task, surf::Keypoints&& keypoints);
    void write_keypoints(const sw::ssa2::Task& task, const surf::Keypoints& keypoints);
    bool kept(size_t frame) const;

    double throughput() const;
    nlohmann::ordered_json evaluation() const;
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
    std::string out_;                   // where keypoint files go as frames are reported ("" : nowhere)
    std::vector<std::string> written_;  // their names, relative to out_
    std::exception_ptr write_failure_;  // the first that failed; no more are handed out after it
                                        // (one on the writer counts from finish_writes())
    // With a worker lent, each file is formatted and written on a thread of the files' own (the
    // simulation's or the software's thread has better to do); finish_writes() waits for them
    // and takes their failure.
    void finish_writes();
    std::unique_ptr<Worker> writer_;
    std::optional<size_t> last_write_;  // the writer's job number of the last file handed to it
    std::mutex write_mutex_;
    std::exception_ptr writer_failure_;  // a file the writer failed to write; under write_mutex_
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
    return {{"source", config_.text("surf.source")},
            {"evaluation", evaluation()},
            {"software_stage", describer_report(*describer_)},
            {"per_frame", frames}};
}

// Feature quality on the chip's own keypoints, when the scenario gives the geometry.
nlohmann::ordered_json SurfWorkload::evaluation() const {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    if (done_ != source_.count) return out;
    const std::string homography = config_.text("eval.homography");
    if (!homography.empty() && results_.size() >= 2) {
        const Eigen::Matrix3d h = eval::read_homography_file(homography);
        const cv::Size size = source_.sizes[0], size_b = source_.sizes[1];
        const auto rep = eval::repeatability(results_[0].keypoints, results_[1].keypoints, h, size, size_b);
        const auto prec = eval::matching_precision(results_[0].keypoints, results_[1].keypoints, h);
        out["homography"] = {{"repeatability", rep.repeatability},
                             {"correspondences", rep.correspondences},
                             {"precision", prec.precision},
                             {"candidates", prec.candidates}};
    }
    const std::string poses = config_.text("eval.poses");
    if (!poses.empty() && results_.size() >= 2) {
        std::vector<surf::Keypoints> all;
        for (const FrameResult& r : results_) all.push_back(r.keypoints);
        const auto posed = eval::list_posed_frames(poses);
        const eval::CameraIntrinsics k = eval::kCastleIntrinsics;
        for (size_t gap : evaluated_gaps(config_)) {
            if (gap >= results_.size()) continue;
            const auto ransac = eval::sequence_distinguishability(all, gap);
            const auto truth = eval::sequence_distinguishability(all, gap, [&](size_t i, size_t j) {
                return eval::fundamental_from_poses(k, posed.at(i).c_m_o, posed.at(j).c_m_o);
            });
            out[fmt::format("distinguishability_gap{}", gap)] = {
                {"ransac", ransac.mean}, {"ground_truth", truth.mean}, {"pairs", ransac.pairs.size()}};
        }
    }
    return out;
}

// Frame i arrives in its task's image buffer; the fault plan learns which frame is there.
void SurfWorkload::deliver(const cv::Mat& frame, const sw::ssa2::Task& task) {
    uint8_t* at = memory_(task.image, uint64_t(frame.cols) * frame.rows);
    for (int y = 0; y < frame.rows; ++y) std::copy_n(frame.ptr(y), frame.cols, at + size_t(y) * frame.cols);
    if (faults_) faults_->frame_arrived(task.image, task.id);
}

// The evaluation needs frames 0 and 1 (a homography) or every frame (camera poses); the
// report's picture frame 0. Keypoints of the others live in their files only.
bool SurfWorkload::kept(size_t frame) const {
    return frame == 0 || (frame == 1 && !config_.text("eval.homography").empty()) ||
           !config_.text("eval.poses").empty();
}

void SurfWorkload::reported(const sw::ssa2::Task& task, surf::Keypoints&& keypoints) {
    FrameResult& r = results_[size_t(task.id)];
    r.task = task;
    r.task.candidates = std::vector<uint32_t>();  // released: a long run keeps their count
    r.keypoint_count = keypoints.size();
    r.reported = true;
    ++done_;
    frame_wall_s_.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - software_start_).count());
    if (task.phase == sw::ssa2::Phase::done) write_keypoints(task, keypoints);  // a failed frame has no keypoints
    if (kept(size_t(task.id))) r.keypoints = std::move(keypoints);
}

// A frame's keypoint file, written as the frame is reported. A write that fails (a full disk)
// is kept for files_written() to throw after the run, and no further file is tried.
void SurfWorkload::write_keypoints(const sw::ssa2::Task& task, const surf::Keypoints& keypoints) {
    if (out_.empty() || write_failure_) return;
    try {
        const fs::path folder = fs::path(out_) / "keypoints";
        if (written_.empty()) fs::create_directories(folder);
        const fs::path file = keypoint_file(out_, task.id);
        written_.push_back(file.lexically_relative(out_).string());
        if (!writer_) return eval::write_keypoint_file(file, keypoints);
        last_write_ = writer_->submit([this, file, keypoints] {
            try {
                eval::write_keypoint_file(file, keypoints);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(write_mutex_);
                if (!writer_failure_) writer_failure_ = std::current_exception();
            }
        });
    } catch (...) {
        write_failure_ = std::current_exception();
    }
}

void SurfWorkload::finish_writes() {
    if (writer_ && last_write_) writer_->wait(*last_write_);
    last_write_.reset();
    const std::lock_guard<std::mutex> lock(write_mutex_);
    if (writer_failure_ && !write_failure_) write_failure_ = writer_failure_;
}

std::vector<std::string> SurfWorkload::files_written() {
    finish_writes();
    if (write_failure_) std::rethrow_exception(write_failure_);
    std::vector<std::string> names = written_;
    std::sort(names.begin(), names.end());  // frames are reported in the order they finish
    return names;
}

}  // namespace

std::unique_ptr<Workload> make_surf_workload(const Config& config) { return std::make_unique<SurfWorkload>(config); }

void for_each_chip_frame(const Config& config, const std::function<void(size_t, const cv::Mat&)>& take) {
    const SourceFrames& source = load_source(config);
    FrameStream stream(config, source);
    for (size_t i = 0; i < source.count; ++i) take(i, stream.frame(i));
}

void check_surf_inputs(const Config& config) {
    if (config.choice("run.workload") != "surf") return;
    check_eval_inputs(config, load_source(config));
}

// Frame 0 at most 640 pixels wide, PNG inline, each keypoint a circle of 2.5 scales with a
// stroke to its orientation (green: dark blob, Laplacian +1; red: bright blob).
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
        "{1}\">"
        "<image width=\"{0}\" height=\"{1}\" href=\"data:image/png;base64,{2}\"/>",
        shown.cols, shown.rows, YAML::EncodeBase64(png.data(), png.size()));
    for (const surf::Keypoint& k : results_[0].keypoints) {
        const double x = (k.x + 0.5) * f, y = (k.y + 0.5) * f, r = std::max(2.0, 2.5 * k.scale * f);
        const char* c = k.laplacian > 0 ? "#00e000" : "#ff3030";
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
    p.upright = c.choice("surf.upright") == "on";
    p.haar = c.choice("surf.haar") == "exact" ? surf::HaarMode::exact : surf::HaarMode::rounded;
    p.max_offset = float(c.real("surf.max_offset"));
    return p;
}

std::string threshold_rule_text(const Config& c, const std::string& whose) {
    const int64_t target = c.count("surf.target_keypoints");
    if (target == 0) return "surf.threshold";
    const std::string first =
        fmt::format("the {}th strongest response {} on frame 0 (surf.target_keypoints)", target, whose);
    if (c.choice("surf.threshold_control") != "track") return first + ", held for every frame";
    const int64_t delay = c.count("surf.tasks_in_flight");
    return fmt::format(
        "{} for the first {} frames, then each from the keypoint count of the frame {} before it "
        "(surf.threshold_control = track)",
        first, delay, delay);
}

fs::path keypoint_file(const fs::path& folder, size_t frame) {
    return folder / "keypoints" / fmt::format("frame_{:04}.surf", frame);
}

}  // namespace surfvp
