#pragma once
// Faults injected on purpose (a scenario's `faults:` section, docs/faults.md), so that the
// driver's detection and recovery can be seen to work. Plain C++: each model asks the plan at
// the point where its fault would strike, and the plan says whether one does; every fault
// strikes once. Blocks know a frame by its image's address (the IIG's SRC at START); the
// workload says which frame each image buffer holds as frames arrive.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/common/frame_status.h"

namespace surfvp {

enum class FaultKind {
    dma_outside_memory,   // the driver gives a block a buffer outside memory: its DMA gets a bus error
    bus_error,            // PLB2 answers a master's Nth burst with an error
    lost_interrupt,       // a block's end-of-frame interrupt never rises
    stuck_interrupt,      // a block's interrupt line stays high until the block is reset
    fifo_overflow,        // the maxima FIFO refuses every candidate of a frame, as if full
    never_finishes,       // a block does its work but never leaves BUSY
    corrupt_determinant,  // the determinant of a frame's first checked candidate is inverted on its way to memory
};

const char* fault_kind_name(FaultKind kind);
std::optional<FaultKind> parse_fault_kind(std::string_view name);
// Every kind, for messages and docs.
const std::vector<FaultKind>& fault_kinds();
// Whether the kind strikes a frame on a block (iig or fhg), or a bus master's burst.
bool strikes_a_frame(FaultKind kind);

struct Fault {
    FaultKind kind = FaultKind::bus_error;
    std::string block;   // iig or fhg; bus_error: the PLB2 master as the bus names it (iig, fhg, iig1, dma)
    uint64_t frame = 0;  // the frame it strikes (counted from 0)
    uint64_t burst = 0;  // bus_error: the master's burst it strikes (1 = its first)
    std::string origin;  // where the scenario gave it (FILE:LINE)

    // What happened, filled in by the plan.
    bool fired = false;
    uint64_t fired_ps = 0;
    int64_t struck_frame = -1;     // the frame it hit (bus_error: the frame its pair was working on)
    std::string describe() const;  // "lost_interrupt on fhg, frame 3"
};

class FaultPlan {
public:
    FaultPlan() = default;
    explicit FaultPlan(std::vector<Fault> faults) : faults_(std::move(faults)) {}

    bool empty() const { return faults_.empty(); }
    const std::vector<Fault>& faults() const { return faults_; }

    // Frame `frame` arrived in the image buffer at `image` (in place of the one before).
    void frame_arrived(uint32_t image, int64_t frame) { images_[image] = frame; }
    // The IIG of accelerator pair `pair` started a frame from image `src`.
    void frame_started(unsigned pair, uint32_t src);
    // The frame pair `pair` works on, -1 before its first.
    int64_t frame_of(unsigned pair) const { return pair < current_.size() ? current_[pair] : -1; }

    // Whether a fault of `kind` strikes `block` ("iig" or "fhg") of `pair` now, on the frame it
    // works on; a fault that does is marked fired at `now_ps`.
    bool strike(FaultKind kind, std::string_view block, unsigned pair, uint64_t now_ps);
    // Whether master `master`'s burst number `burst` (1 = its first) gets an error response.
    bool bus_error(std::string_view master, uint64_t burst, uint64_t now_ps);
    // A fault the software carries out itself (dma_outside_memory: the driver is given the
    // buffer), on its frame, now.
    void strike_in_software(size_t index, uint64_t now_ps);

private:
    void fire(Fault& fault, int64_t frame, uint64_t now_ps);

    std::vector<Fault> faults_;
    std::map<uint32_t, int64_t> images_;  // image buffer -> the frame in it
    std::vector<int64_t> current_;
};

// One IP block's side of the plan (the IIG's or the FHG's of a pair): whether a fault strikes
// it now, and the injected faults in effect on its STATUS and interrupt line.
class BlockFaults {
public:
    explicit BlockFaults(const char* block) : block_(block) {}
    void attach(FaultPlan* plan, unsigned pair) {
        plan_ = plan;
        pair_ = pair;
    }
    bool attached() const { return plan_ != nullptr; }
    bool strikes(FaultKind kind, uint64_t now_ps) const { return plan_ && plan_->strike(kind, block_, pair_, now_ps); }
    FaultPlan& plan() const { return *plan_; }
    unsigned pair() const { return pair_; }
    // The interrupt line the INTC sees: stuck high, or the block's own line unless lost.
    bool line(bool raised) const { return irq_stuck || (raised && !irq_lost); }

    // CTRL.RESET, as both blocks take it: a frame that never ended (hung) is dropped, STATUS
    // cleared and `busy` (the block's BUSY signal) low; one in progress is ended by `abort`;
    // a stuck or lost interrupt lets go. The block then drives its line again.
    template <class Busy, class Abort>
    void reset(FrameStatus& status, Busy& busy, const Abort& abort) {
        if (hung) {
            hung = false;
            status.reset();
            busy.write(false);
        } else if (status.busy()) {
            abort();
        }
        irq_stuck = irq_lost = false;
    }

    bool hung = false;       // the frame's end withheld: STATUS stays BUSY until CTRL.RESET
    bool irq_lost = false;   // the frame's end raises no interrupt
    bool irq_stuck = false;  // the line stays high until CTRL.RESET

private:
    const char* block_;
    FaultPlan* plan_ = nullptr;
    unsigned pair_ = 0;
};

// The pair a block or master name belongs to: "fhg" 0, "iig1" 1; nullopt for others (dma, cpu).
std::optional<unsigned> pair_of(std::string_view name);

}  // namespace surfvp
