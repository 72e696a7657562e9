#include "libssa2.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "models/fhg/fhg_regs.h"
#include "models/iig/iig_regs.h"
#include "models/intc/intc_regs.h"

namespace surfvp::sw::ssa2 {
namespace f = fhg_regs;

namespace {

// Register polls after a CTRL.RESET before the driver gives up on a pair: an aborted frame
// runs out within its DMA in flight, a few hundred polls at PLB1's speed.
constexpr unsigned kResetPolls = 100000;

const char* fhg_error(uint32_t code) {
    switch (code) {
        case f::ERR_WRITE:
            return "FHG determinant DMA write got a bus error";
        case f::ERR_SIZE:
            return "FHG refused the image size";
        case f::ERR_START_BUSY:
            return "FHG was started while busy";
        case f::ERR_ABORTED:
            return "FHG aborted";
        case f::ERR_PIXELBUS:
            return "FHG got a PixelBus line of the wrong width";
        default:
            return "FHG error";
    }
}

const char* iig_error(uint32_t code) {
    switch (code) {
        case iig::ERR_READ:
            return "IIG image DMA read got a bus error";
        case iig::ERR_WRITE:
            return "IIG integral DMA write got a bus error";
        case iig::ERR_OVERFLOW:
            return "IIG integral sum overflowed its word";
        case iig::ERR_SIZE:
            return "IIG refused the image size";
        case iig::ERR_START_BUSY:
            return "IIG was started while busy";
        case iig::ERR_ABORTED:
            return "IIG aborted";
        default:
            return "IIG error";
    }
}

}  // namespace

Driver::Driver(Hal& hal, DriverConfig config, Describer& describer)
    : hal_(hal),
      config_(std::move(config)),
      describer_(describer),
      running_(config_.accelerators.size(), -1),
      set_busy_(config_.buffers.size(), false),
      time_(config_.accelerators.size()),
      since_(config_.accelerators.size(), 0) {
    if (config_.accelerators.empty()) throw std::invalid_argument("libSSA2 needs at least one accelerator");
    if (config_.buffers.empty()) throw std::invalid_argument("libSSA2 needs at least one buffer set");
}

void Driver::enable_interrupts() {
    Span span(hal_, "init interrupts");
    uint32_t mask = 0;
    for (const Accelerator& a : config_.accelerators) mask |= 1u << a.iig_irq | 1u << a.fhg_irq;
    hal_.write32(config_.intc_base + intc::IER, mask);
    formats_.clear();
    for (const Accelerator& a : config_.accelerators)
        formats_.push_back({hal_.read32(a.fhg_base + f::DET_BYTES), hal_.read32(a.fhg_base + f::DET_FRAC_BITS)});
    hal_.write32(config_.intc_base + intc::MER, intc::MER_ME | intc::MER_HIE);
}

void Driver::run(std::vector<Task>& tasks, const Camera& camera, const Callback& callback) {
    keypoints_.assign(tasks.size(), {});
    learned_.assign(tasks.size(), std::nullopt);
    spurious_.assign(32, 0);
    for (size_t i = 0; i < tasks.size(); ++i) tasks[i].id = int(i);
    enable_interrupts();
    auto unfinished = [&] {
        for (const Task& t : tasks)
            if (t.phase != Phase::done && t.phase != Phase::failed) return true;
        return false;
    };
    while (unfinished()) {
        start_hardware(tasks, camera);
        for (size_t a = 0; a < running_.size(); ++a)
            if (running_[a] < 0) account(a, queued(tasks) ? time_[a].waiting_for_buffers_ps : time_[a].idle_ps);
        if (hal_.irq_pending()) {
            service_interrupts(tasks);
        } else if (Task* t = describing(tasks)) {
            describe_one(*t, callback);
        } else {
            Span span(hal_, "idle");
            if (!hal_.wait_for_irq(watchdog_timeout(tasks))) watchdog(tasks);
        }
        // Tasks that failed are reported as soon as their accelerator has let go of them.
        for (Task& t : tasks)
            if (t.phase == Phase::failed && t.accelerator < 0 && t.t_done == 0) finish(t, callback);
    }
}

// Adds the time since the last account of pair `a` to `bucket`.
void Driver::account(size_t a, uint64_t& bucket) {
    const uint64_t now = hal_.time_ps();
    bucket += now - since_[a];
    since_[a] = now;
}

bool Driver::queued(const std::vector<Task>& tasks) {
    return std::any_of(tasks.begin(), tasks.end(), [](const Task& t) { return t.phase == Phase::queued; });
}

// A queued task starts on a free pair when a buffer set is free: a set stays with its task
// until the task is reported, so a failed task cannot let the next one overwrite buffers
// the CPU is still reading.
void Driver::start_hardware(std::vector<Task>& tasks, const Camera& camera) {
    for (size_t a = 0; a < running_.size(); ++a) {
        if (running_[a] >= 0) continue;
        const auto set = std::find(set_busy_.begin(), set_busy_.end(), false);
        if (set == set_busy_.end()) return;
        for (Task& t : tasks)
            if (t.phase == Phase::queued) {
                t.buffer_set = int(set - set_busy_.begin());
                *set = true;
                t.image = config_.buffers[size_t(t.buffer_set)].image;
                t.threshold = threshold_for(t.id);
                camera(t);
                start(t, int(a));
                break;
            }
    }
}

void Driver::start(Task& task, int accelerator) {
    Span span(hal_, "start hardware");
    const Accelerator& a = config_.accelerators[accelerator];
    task.phase = Phase::hardware;
    task.accelerator = accelerator;
    task.described_on = accelerator;
    account(size_t(accelerator), time_[size_t(accelerator)].waiting_for_buffers_ps);  // free until now, a task waiting
    running_[accelerator] = task.id;
    hal_.mark(unsigned(accelerator), task.id);
    task.t_start = hal_.time_ps();
    const BufferSet& buffers = config_.buffers[size_t(task.buffer_set)];
    task.watchdog_at = task.t_start + config_.watchdog_ps;
    task.records = buffers.records;
    // A preset buffer stays (fault injection: dma_outside_memory).
    if (task.integral == 0) task.integral = buffers.integral;
    if (task.determinants == 0) task.determinants = buffers.determinants;
    // The FHG first: it must be listening before the IIG streams.
    hal_.write32(a.fhg_base + f::DET_ADDR, task.determinants);
    hal_.write32(a.fhg_base + f::WIDTH, uint32_t(task.width));
    hal_.write32(a.fhg_base + f::HEIGHT, uint32_t(task.height));
    hal_.write32(a.fhg_base + f::THRESHOLD, uint32_t(task.threshold));
    hal_.write32(a.fhg_base + f::FIFO_THRESHOLD, config_.fifo_irq_level);
    hal_.write32(a.fhg_base + f::CTRL, f::CTRL_START | f::CTRL_IRQ_EN_DONE | f::CTRL_IRQ_EN_FIFO);
    hal_.write32(a.iig_base + iig::SRC, task.image);
    hal_.write32(a.iig_base + iig::DST, task.integral);
    hal_.write32(a.iig_base + iig::WIDTH, uint32_t(task.width));
    hal_.write32(a.iig_base + iig::HEIGHT, uint32_t(task.height));
    hal_.write32(a.iig_base + iig::SRC_STRIDE, uint32_t(task.width));
    hal_.write32(a.iig_base + iig::DST_STRIDE, uint32_t(task.width) * 4);
    hal_.write32(a.iig_base + iig::CTRL, iig::CTRL_START | iig::CTRL_IRQ_EN | iig::CTRL_STREAM);
}

void Driver::service_interrupts(std::vector<Task>& tasks) {
    Span span(hal_, "interrupt");
    ++interrupts_;
    const uint32_t pending = hal_.read32(config_.intc_base + intc::IPR);
    for (size_t i = 0; i < config_.accelerators.size(); ++i) {
        const Accelerator& a = config_.accelerators[i];
        for (const bool fhg : {true, false}) {
            const unsigned line = fhg ? a.fhg_irq : a.iig_irq;
            if (!(pending & (1u << line))) continue;
            Task* task = running_[i] >= 0 ? &tasks[size_t(running_[i])] : nullptr;
            if (task && (fhg ? on_fhg(*task, a) : on_iig(*task, a)))
                spurious_[line] = 0;
            else
                spurious(tasks, i, fhg);
        }
        if (running_[i] < 0) continue;
        Task& task = tasks[size_t(running_[i])];
        if (task.integral_done && task.determinants_done) hardware_finished(task);
    }
    // Acknowledge after the sources have let go of their lines (they are level sensitive).
    hal_.write32(config_.intc_base + intc::IAR, pending);
}

// An interrupt with nothing to serve (one can follow a line that has just let go). Many in a
// row: the line is stuck; the pair's task fails and the pair's reset lets the line go.
void Driver::spurious(std::vector<Task>& tasks, size_t i, bool fhg) {
    ++recovery_.spurious_interrupts;
    const Accelerator& a = config_.accelerators[i];
    unsigned& in_a_row = spurious_[fhg ? a.fhg_irq : a.iig_irq];
    if (config_.spurious_irq_limit == 0 || ++in_a_row < config_.spurious_irq_limit) return;
    in_a_row = 0;
    if (running_[i] < 0) return reset_pair(i);
    Task& task = tasks[size_t(running_[i])];
    fail(task, fmt::format("the {}'s interrupt line is stuck: {} interrupts in a row with nothing to serve",
                           fhg ? "FHG" : "IIG", config_.spurious_irq_limit));
    task.integral_done = task.determinants_done = true;
    hardware_finished(task);
}

// The time until the earliest watchdog of a task in hardware.
uint64_t Driver::watchdog_timeout(const std::vector<Task>& tasks) {
    if (config_.watchdog_ps == 0) return Hal::kNoTimeout;
    uint64_t due = Hal::kNoTimeout;
    for (const int id : running_)
        if (id >= 0) due = std::min(due, tasks[size_t(id)].watchdog_at);
    const uint64_t now = hal_.time_ps();
    return due == Hal::kNoTimeout ? due : due > now ? due - now : 0;
}

// A task's hardware has run longer than the watchdog. A block found finished had its
// interrupt lost: it is served now and the task goes on. A block still BUSY never finishes:
// the task fails and the pair is reset. Without time (direct mode) every task in hardware is due.
void Driver::watchdog(std::vector<Task>& tasks) {
    Span span(hal_, "watchdog");
    const uint64_t now = hal_.time_ps();
    for (size_t i = 0; i < running_.size(); ++i) {
        if (running_[i] < 0) continue;
        Task& task = tasks[size_t(running_[i])];
        if (now != 0 && task.watchdog_at > now) continue;
        ++recovery_.watchdog_expiries;
        const Accelerator& a = config_.accelerators[i];
        const bool iig_ended =
            !task.integral_done && (hal_.read32(a.iig_base + iig::STATUS) & (iig::STATUS_DONE | iig::STATUS_ERROR));
        const bool fhg_ended =
            !task.determinants_done && (hal_.read32(a.fhg_base + f::STATUS) & (f::STATUS_DONE | f::STATUS_ERROR));
        for (const auto& [ended, block] : {std::pair{iig_ended, "IIG"}, std::pair{fhg_ended, "FHG"}})
            if (ended)
                task.incidents.push_back(
                    fmt::format("the {}'s interrupt was lost: the watchdog found it finished", block));
        if (iig_ended) on_iig(task, a);
        if (fhg_ended) on_fhg(task, a);
        if (iig_ended || fhg_ended) {
            task.watchdog_at = now + config_.watchdog_ps;
        } else {
            const char* which = !task.integral_done && !task.determinants_done ? "IIG and the FHG"
                                : !task.integral_done                          ? "IIG"
                                                                               : "FHG";
            fail(task, fmt::format("the {} did not finish within the watchdog ({:g} ms)", which,
                                   double(config_.watchdog_ps) * 1e-9));
            task.integral_done = task.determinants_done = true;
        }
        if (task.integral_done && task.determinants_done) hardware_finished(task);
    }
}

// CTRL.RESET to both blocks of a pair; a frame in progress is aborted and runs out, so the
// blocks are polled until neither is BUSY and reset again, which clears them.
void Driver::reset_pair(size_t i) {
    Span span(hal_, "reset");
    ++recovery_.pair_resets;
    const Accelerator& a = config_.accelerators[i];
    auto reset = [&] {
        hal_.write32(a.fhg_base + f::CTRL, f::CTRL_RESET);
        hal_.write32(a.iig_base + iig::CTRL, iig::CTRL_RESET);
    };
    reset();
    for (unsigned polls = 0; (hal_.read32(a.fhg_base + f::STATUS) & f::STATUS_BUSY) ||
                             (hal_.read32(a.iig_base + iig::STATUS) & iig::STATUS_BUSY);
         ++polls)
        if (polls == kResetPolls)
            throw std::runtime_error(fmt::format("libSSA2: accelerator pair {} stays BUSY after CTRL.RESET", i));
    reset();
}

size_t Driver::drain_fifo(Task& task, const Accelerator& a) {
    const uint32_t level = hal_.read32(a.fhg_base + f::FIFO_LEVEL);
    for (uint32_t i = 0; i < level; ++i) {
        const uint32_t word = hal_.read32(a.fhg_base + f::FIFO_DATA);
        if (word >> 31) task.candidates.push_back(word);
    }
    return level;
}

// Both return whether there was anything to serve.
bool Driver::on_fhg(Task& task, const Accelerator& a) {
    const uint32_t status = hal_.read32(a.fhg_base + f::STATUS);
    const size_t drained = drain_fifo(task, a);
    if (!(status & (f::STATUS_DONE | f::STATUS_ERROR))) return drained > 0;
    drain_fifo(task, a);  // what arrived after the first read-out
    task.t_determinants = hal_.time_ps();
    task.determinants_done = true;
    if (status & f::STATUS_ERROR) {
        fail(task, fhg_error(hal_.read32(a.fhg_base + f::ERROR_CODE)));
        hal_.write32(a.iig_base + iig::CTRL, iig::CTRL_ABORT | iig::CTRL_IRQ_EN);
    } else if (const uint32_t dropped = hal_.read32(a.fhg_base + f::OVERFLOW_COUNT)) {
        fail(task, fmt::format("the maxima FIFO overflowed: {} candidates dropped", dropped));
    }
    hal_.write32(a.fhg_base + f::STATUS, f::STATUS_DONE | f::STATUS_ERROR | f::STATUS_FIFO_OVERFLOW);
    return true;
}

bool Driver::on_iig(Task& task, const Accelerator& a) {
    const uint32_t status = hal_.read32(a.iig_base + iig::STATUS);
    if (!(status & (iig::STATUS_DONE | iig::STATUS_ERROR))) return false;
    task.t_integral = hal_.time_ps();
    task.integral_done = true;
    if (status & iig::STATUS_ERROR) {
        const uint32_t code = hal_.read32(a.iig_base + iig::ERROR_CODE);
        if (code != iig::ERR_ABORTED) fail(task, iig_error(code));
        hal_.write32(a.fhg_base + f::CTRL,
                     f::CTRL_ABORT | f::CTRL_IRQ_EN_DONE);  // the FHG waits for lines that will not come
    }
    hal_.write32(a.iig_base + iig::STATUS, iig::STATUS_DONE | iig::STATUS_ERROR);
    return true;
}

void Driver::fail(Task& task, const std::string& why) {
    if (task.phase == Phase::failed) return;  // the first reason stands
    task.phase = Phase::failed;
    task.error = why;
}

// Both units are done with the task: the pair is free (reset first when the task failed),
// and the CPU may describe it.
void Driver::hardware_finished(Task& task) {
    if (task.phase == Phase::failed) reset_pair(size_t(task.accelerator));
    account(size_t(task.accelerator), time_[size_t(task.accelerator)].working_ps);
    running_[size_t(task.accelerator)] = -1;
    hal_.mark(unsigned(task.accelerator), -1);
    task.accelerator = -1;
    if (task.phase == Phase::hardware) task.phase = Phase::descriptors;
}

Task* Driver::describing(std::vector<Task>& tasks) {
    for (Task& t : tasks)
        if (t.phase == Phase::descriptors) return &t;
    return nullptr;
}

// One candidate at a time, so that interrupts are served between them.
// With one accelerator pair tasks reach phase 4 in their order, so a task's candidates are
// described one after the other (describing() takes the first task in phase 4), and the
// describer may work on them ahead.
void Driver::describe_one(Task& task, const Callback& callback) {
    const Format& format = formats_[size_t(task.described_on)];
    const FrameInMemory frame{task.id,     task.integral,    task.determinants,    task.records,  task.width,
                              task.height, format.det_bytes, format.det_frac_bits, task.threshold};
    if (task.described == 0) {
        hal_.mark(unsigned(config_.accelerators.size()), task.id);
        if (config_.accelerators.size() == 1 && !task.candidates.empty())
            describer_.ahead(hal_, task.candidates, frame);
    }
    if (task.described < task.candidates.size()) {
        Span span(hal_, "describe");
        Work work;
        auto keypoint = describer_.describe(hal_, task.candidates[task.described++], frame, work);
        hal_.split_next_compute(work.steps);
        task.descriptor_cycles += hal_.compute(work.cycles, work.lines, work.untimed_fills);
        if (keypoint) keypoints_[size_t(task.id)].push_back(*keypoint);
        if (!work.inconsistency.empty()) {  // the hardware's results cannot be trusted: no keypoints from them
            fail(task, "software check: " + work.inconsistency);
            keypoints_[size_t(task.id)].clear();
            hal_.mark(unsigned(config_.accelerators.size()), -1);
            return finish(task, callback);
        }
    }
    if (task.described == task.candidates.size()) {
        hal_.mark(unsigned(config_.accelerators.size()), -1);
        task.phase = Phase::done;
        finish(task, callback);
    }
}

// The keypoint-count control. Task n runs with the THRESHOLD that the count of task n - S
// (S buffer sets) asked for: with one accelerator pair tasks are reported in order, and task
// n starts only once a set is free, so task n - S has always been reported then, in the VP
// and in direct mode alike; the result does not depend on timing. A task n - S that failed,
// or (with several pairs, reported out of order) is not reported yet, leaves the THRESHOLD the
// task before had.
int32_t Driver::threshold_for(int task) {
    if (config_.keypoint_target == 0) return config_.threshold;
    if (task == 0) last_threshold_ = config_.threshold;
    const int from = task - int(config_.buffers.size());
    if (from >= 0 && learned_[size_t(from)]) last_threshold_ = *learned_[size_t(from)];
    return last_threshold_;
}

double keypoint_control_step(double threshold, size_t count, uint32_t target) {
    const double t = std::max(threshold, 1e-9);
    return std::clamp(t * std::sqrt(double(count) / double(target)), t / 2, t * 2);
}

void Driver::finish(Task& task, const Callback& callback) {
    if (task.buffer_set >= 0) set_busy_[size_t(task.buffer_set)] = false;
    if (config_.keypoint_target && task.phase == Phase::done)
        learned_[size_t(task.id)] = int32_t(std::clamp<double>(
            std::round(keypoint_control_step(std::max<int32_t>(task.threshold, 1), keypoints_[size_t(task.id)].size(),
                                             config_.keypoint_target)),
            1, INT32_MAX));  // never 0: a threshold of 0 would stay 0
    task.t_done = hal_.time_ps();
    if (task.t_done == 0) task.t_done = 1;  // direct mode has no time: mark it reported
    task.candidate_count = task.candidates.size();
    callback(task, std::move(keypoints_[size_t(task.id)]));
    // Released, not cleared (`= {}` would keep the capacity).
    keypoints_[size_t(task.id)] = surf::Keypoints();
    task.candidates = std::vector<uint32_t>();
}

}  // namespace surfvp::sw::ssa2
