#pragma once
// libSSA2, the driver of the SSA IIG / SSA FHG accelerators (paper §III-D), written against
// the HAL only: registers, memory and interrupts.
//
// A task is one image: its buffers in memory (image, integral image, determinants) and its
// results. Processing has the paper's four phases:
//   1. integral image      the IIG, streaming into the FHG          (hardware)
//   2. determinants        the FHG                                   (hardware)
//   3. local maxima        draining the FHG's maxima FIFO on its occupancy interrupt, and
//                          what is left when the FHG is done        (CPU, interrupt-driven)
//   4. descriptors         the software stage on every candidate     (CPU)
// Phases overlap, and so do tasks: while the CPU describes task n, the accelerators already
// work on task n+1 (as many tasks between start and end as there are buffer sets). With several
// accelerator pairs, tasks go to whichever pair is free.
//
// What goes wrong fails that task with its reason, and the others go on: a block's ERROR (bus
// error, size), the maxima FIFO's overflow, a watchdog (a task's hardware not finished within
// `watchdog_ps`: a block that is found finished had its interrupt lost and the task goes on;
// one still BUSY never finishes), an interrupt line that keeps asking with nothing to serve
// (stuck), and the software stage's check of the determinants it reads. A pair whose task
// failed in hardware is reset through its CTRL.RESET before it takes the next task.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "models/common/hal.h"
#include "sw/surf/keypoint.h"

namespace surfvp::sw::ssa2 {

struct Accelerator {
    uint32_t iig_base, fhg_base;  // register windows
    unsigned iig_irq, fhg_irq;    // INTC input numbers
};

// One set of buffers in memory; a task holds one from its start until it is reported. Its
// frame arrives in `image` when it starts (the Camera below), so a run of any length needs
// only as many frame buffers as tasks in flight.
struct BufferSet {
    uint32_t image;  // the frame, width x height bytes
    uint32_t integral, determinants;
    uint32_t records;  // the ring the descriptors are written to for the application (kRecordRing records)
};

// A described keypoint as libSSA2 hands it over: x, y, scale, orientation, response,
// Laplacian and 64 descriptor values, 32-bit each, in a per-task ring of kRecordRing slots of
// kRecordSlot bytes (whole cache lines of up to 256 bytes, so no two records share a line; the
// application consumes them through the callback before the ring wraps).
constexpr uint32_t kRecordBytes = (6 + 64) * 4;
constexpr uint32_t kRecordSlot = 512;
constexpr uint32_t kRecordRing = 256;

struct DriverConfig {
    uint32_t intc_base = 0;
    std::vector<Accelerator> accelerators;
    std::vector<BufferSet> buffers;  // as many tasks are in flight as there are sets
    uint32_t fifo_irq_level = 256;   // FHG FIFO_THRESHOLD
    int32_t threshold = 0;           // FHG THRESHOLD (determinant fixed point) of the first task, or of every task
    // 0: every task runs with `threshold`. N: a keypoint-count control, as a camera pipeline
    // holds its feature count: each task's THRESHOLD is the one the keypoint count of an earlier
    // task asked for (Driver::threshold_for).
    uint32_t keypoint_target = 0;
    uint64_t watchdog_ps = 0;         // a task's hardware longer than this is checked (0: never)
    unsigned spurious_irq_limit = 0;  // interrupts in a row with nothing to serve that make a line stuck (0: never)
    // HAL markers: accelerator k's task is marker k (-1 when idle); the task being described
    // is marker accelerators.size() (-1 when none).
};

// Where the hardware left one task's results, as the software stage reads them.
struct FrameInMemory {
    int task;                         // which task: new buffers when it changes
    uint32_t integral, determinants;  // bus addresses
    uint32_t records;                 // the task's descriptor ring
    int width, height;
    uint32_t det_bytes, det_frac_bits;  // the FHG's determinant format (its DET_BYTES, DET_FRAC_BITS)
    int32_t threshold;                  // the THRESHOLD the FHG ran with, in that format
};

// What describing one candidate cost: the CPU's work and the L1 traffic it caused (line
// fills of the buffers it read, write-backs of the descriptor it wrote), which the driver
// hands to Hal::compute.
struct Work {
    uint64_t cycles = 0;
    std::vector<LineTransfer> lines;
    uint64_t untimed_fills = 0;  // fills not in `lines`, for a platform that does not time them (Hal::times_fills)
    std::string inconsistency;   // the software's check of the hardware's results failed: why
    std::vector<std::pair<const char*, uint64_t>> steps;  // cycles by step, for the CPU's phase in the trace
};

// The CPU's part of phase 4 (sw/stage): one candidate word -> a keypoint or none. It reads
// the frame through hal.map() and says what its work cost.
class Describer {
public:
    virtual ~Describer() = default;
    virtual std::optional<surf::Keypoint> describe(Hal& hal, uint32_t candidate, const FrameInMemory& frame,
                                                   Work& work) = 0;
    // Before a task's first describe(), when the driver will describe its candidates one after
    // the other, without another task's between them, until the last or the first whose check
    // fails (Work::inconsistency): a describer may work on them ahead, as long as each
    // describe() then gives what it would have given alone. The task's buffers are not written
    // until it is reported.
    virtual void ahead(Hal& /*hal*/, const std::vector<uint32_t>& /*candidates*/, const FrameInMemory& /*frame*/) {}
};

enum class Phase { queued, hardware, descriptors, done, failed };

struct Task {
    int id = 0;
    uint32_t image = 0;  // its buffer set's image, from its start
    uint32_t integral = 0,
             determinants = 0;  // from a free buffer set at start (a preset determinants: fault injection)
    uint32_t records = 0;
    int width = 0, height = 0;

    Phase phase = Phase::queued;
    int accelerator = -1;   // the pair working on it, -1 once it is done with it
    int described_on = -1;  // the pair whose results it holds (its determinant format)
    int buffer_set = -1;
    int32_t threshold = 0;               // the FHG THRESHOLD it ran with
    std::string error;                   // why it failed
    std::vector<std::string> incidents;  // what went wrong and was recovered from (a lost interrupt)
    uint64_t watchdog_at = 0;            // when its hardware is checked next (ps)
    std::vector<uint32_t> candidates;    // maxima FIFO words, in FIFO order (released once reported)
    size_t candidate_count = 0;          // how many the FIFO gave
    size_t described = 0;                // candidates handed to the describer so far
    uint64_t descriptor_cycles = 0;
    bool integral_done = false, determinants_done = false;
    // Time base (ps): hardware start, IIG done, FHG done, descriptors done.
    uint64_t t_start = 0, t_integral = 0, t_determinants = 0, t_done = 0;
};

// The keypoint-count control's step: the threshold for later frames from one frame's
// threshold and keypoint count. At the tail of the Hessian responses the count falls roughly
// in inverse proportion to the threshold, so t x count / target would aim straight at the
// target; the frame it acts on comes a few frames later (Driver::threshold_for), and a full
// step through that delay oscillates, so half the step in proportion: t x sqrt(count /
// target) (IEEE sqrt is exact to the last bit, so every platform gives the same register), at
// most a factor of 2 either way, so one odd frame (a cut, a blur) does not throw it off.
double keypoint_control_step(double threshold, size_t count, uint32_t target);

using Callback = std::function<void(const Task& task, surf::Keypoints&& keypoints)>;
// The application's camera: puts the task's frame at task.image when the task starts (its
// DMA into memory is not modelled: no time, no bus traffic).
using Camera = std::function<void(const Task& task)>;

// Where one accelerator pair's time went, by the driver's clock (Hal::time_ps): working on a
// task, free while a task was queued but every buffer set was still held by a task not yet
// reported (the tasks-in-flight limit), or free with nothing queued.
struct AcceleratorTime {
    uint64_t working_ps = 0, waiting_for_buffers_ps = 0, idle_ps = 0;
};

class Driver {
public:
    Driver(Hal& hal, DriverConfig config, Describer& describer);

    // Runs every task to its end (done or failed), calling `camera` as each starts and
    // `callback` once per task in the order they finish (a finished task's candidates are
    // released after its callback: a long run keeps only their count).
    void run(std::vector<Task>& tasks, const Camera& camera, const Callback& callback);

    uint64_t interrupts_served() const { return interrupts_; }
    // What the driver's detection did: watchdog expiries, interrupts with nothing to serve,
    // and CTRL.RESETs of a pair.
    struct Recovery {
        uint64_t watchdog_expiries = 0, spurious_interrupts = 0, pair_resets = 0;
    };
    const Recovery& recovery() const { return recovery_; }
    const std::vector<AcceleratorTime>& accelerator_time() const { return time_; }

private:
    void enable_interrupts();
    void start_hardware(std::vector<Task>& tasks, const Camera& camera);
    void start(Task& task, int accelerator);
    void service_interrupts(std::vector<Task>& tasks);
    void spurious(std::vector<Task>& tasks, size_t accelerator, bool fhg);
    uint64_t watchdog_timeout(const std::vector<Task>& tasks);
    void watchdog(std::vector<Task>& tasks);
    void reset_pair(size_t accelerator);
    bool on_fhg(Task& task, const Accelerator& a);
    bool on_iig(Task& task, const Accelerator& a);
    size_t drain_fifo(Task& task, const Accelerator& a);
    void fail(Task& task, const std::string& why);
    void hardware_finished(Task& task);
    Task* describing(std::vector<Task>& tasks);
    void describe_one(Task& task, const Callback& callback);
    void finish(Task& task, const Callback& callback);

    Hal& hal_;
    DriverConfig config_;
    Describer& describer_;
    std::vector<int> running_;  // per accelerator: the task it works on, or -1
    struct Format {
        uint32_t det_bytes, det_frac_bits;
    };
    std::vector<Format> formats_;  // per accelerator, read from its registers at the start
    std::vector<bool> set_busy_;   // per buffer set
    std::vector<AcceleratorTime> time_;
    std::vector<uint64_t> since_;  // per accelerator: when it last started or stopped a task
    void account(size_t accelerator, uint64_t& bucket);
    int32_t threshold_for(int task);
    // Per task: the THRESHOLD its keypoint count asks of a later task (set once it is done).
    std::vector<std::optional<int32_t>> learned_;
    int32_t last_threshold_ = 0;  // the one the last task started with
    static bool queued(const std::vector<Task>& tasks);
    std::vector<surf::Keypoints> keypoints_;
    uint64_t interrupts_ = 0;
    std::vector<unsigned> spurious_;  // per INTC line: interrupts in a row with nothing to serve
    Recovery recovery_;
};

}  // namespace surfvp::sw::ssa2
