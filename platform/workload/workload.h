#pragma once
// What the CPU runs in a scenario, and what the run is judged on. Each workload builds its
// software (against the HAL only), says how far it has come, and lists its checks.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "platform/scenario/config.h"
#include "models/common/fault_plan.h"
#include "models/common/tracer.h"
#include "models/ppc440/ppc440.h"
#include "sw/surf/params.h"

namespace cv {
class Mat;  // for_each_chip_frame (this header is also built without OpenCV's include path: tests/fuzz)
}

namespace surfvp {

class Worker;

struct Check {
    std::string name;
    bool passed;
    std::string detail;
    // A goal the design may miss (the frame-rate budget, a keypoint target): a miss is the
    // design's answer (exit 1). Otherwise the check holds the run itself (every frame
    // processed, every fault recovered): a miss means the run broke (exit 6).
    bool goal = false;
};

struct Progress {
    uint64_t done = 0;
    uint64_t total = 0;
    std::string unit;  // "copies", "frames"
};

// Untimed access to memory: what a loader puts there before the run, or a camera as frames
// arrive.
using Backdoor = std::function<uint8_t*(uint64_t address, uint64_t bytes)>;

class Workload {
public:
    virtual ~Workload() = default;
    // Memory, given before software() runs; a workload may keep it for the run.
    virtual void attach_memory(const Backdoor&) {}
    // The faults the scenario injects (the platform hands them to the blocks as well): the
    // workload tells the plan its frames, and reports what became of each.
    virtual void inject(FaultPlan&) {}
    // The simulator's second thread (run.parallel), for work the workload's software can do
    // ahead of the simulation in the thread's idle time; nullptr takes it back, and nothing of
    // the workload runs on it after that. Lent through WorkerLoan.
    virtual void share_worker(Worker*) {}
    virtual Ppc440::Software software() = 0;
    virtual Progress progress() const = 0;
    virtual std::vector<Check> checks() const = 0;
    virtual nlohmann::ordered_json report() const = 0;  // the workload's own section
    // Top-level report keys (frame rate, latency, budget...): none by default.
    virtual nlohmann::ordered_json summary() const { return nlohmann::ordered_json::object(); }
    // Its own timeline tracks, after the run (frames across the blocks).
    virtual void trace(Tracer&) const {}
    // Files of its own (keypoints) go under `dir` as they are made; given before software()
    // runs, or never (then none are written).
    virtual void write_into(const std::string& /*dir*/) {}
    // After the run: the names written under that folder. Throws the first write that failed.
    virtual std::vector<std::string> files_written() { return {}; }
    // Its first frame with what it found drawn on it, as an <svg> element for report.html
    // (the image inline): "" when it has none.
    virtual std::string first_frame_svg() const { return ""; }
};

// Lends a worker to a workload for the loan's lifetime: the owner of the worker and of the
// memory the workload reads holds the loan and ends it before either goes.
class WorkerLoan {
public:
    WorkerLoan(Workload& workload, Worker* worker) : workload_(workload) { workload_.share_worker(worker); }
    ~WorkerLoan() { workload_.share_worker(nullptr); }
    WorkerLoan(const WorkerLoan&) = delete;
    WorkerLoan& operator=(const WorkerLoan&) = delete;

private:
    Workload& workload_;
};

// The workload `run.workload` names; throws ConfigError when its parameters do not fit the
// platform (a buffer outside memory, say).
std::unique_ptr<Workload> make_workload(const Config& config);
std::unique_ptr<Workload> make_surf_workload(const Config& config);

// The files a SURF scenario names (surf.source, eval.homography, eval.poses), read and checked
// against the parameters and the chip's limits, so that nothing a run could find in them is
// found after simulating; throws ConfigError naming the key's origin. Nothing for other
// workloads.
void check_surf_inputs(const Config& config);

// Every frame of surf.source as the chip takes it (grey, resized as surf.width x surf.height
// ask), in order, one decoded at a time: what a run gives the chip, for a reference beside it.
void for_each_chip_frame(const Config& config, const std::function<void(size_t, const cv::Mat&)>& take);

// The chip's software in float (sw/surf): the paper's SURF on the FHG's 2 octaves of 4
// intervals, with the scenario's Haar wavelets (surf.haar), interpolation limit
// (surf.max_offset) and upright setting. The threshold calibration runs it on frame 0; table2
// gives its column beside the chip's.
surf::Params chip_surf_params(const Config& config);

// How a column's threshold is chosen under the scenario's rule (surf.target_keypoints,
// surf.threshold_control), in words; `whose` names the responses ranked on frame 0.
std::string threshold_rule_text(const Config& config, const std::string& whose);

}  // namespace surfvp
