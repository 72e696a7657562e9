#pragma once
// The SSA FHG's register behaviour (the table in fhg_regs.h) and its maxima FIFO: what a
// START, an ABORT, a STATUS write and a FIFO_DATA read do, how candidates enter the FIFO
// (dropped and counted when it is full), and when the interrupt line is high. Plain C++: the
// SystemC model and direct mode both own one, so the FIFO's depth, its counters and its
// overflow are the same in both.
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "fhg_regs.h"
#include "local_max_finder.h"
#include "models/common/frame_status.h"
#include "models/common/register_bank.h"

namespace surfvp {

class FhgRegisters {
public:
    struct Limits {
        unsigned max_width = 1024, max_height = 1024;
        unsigned fifo_depth = 1024;  // maxima FIFO entries
        unsigned det_frac_bits = 0, det_bytes = 4;
    };
    // The frame's registers as START latched them.
    struct Frame {
        uint32_t det_addr, width, height;
        int32_t threshold;
    };
    using Hooks = FrameHooks<Frame>;

    FhgRegisters(const Limits& limits, Hooks hooks);
    FhgRegisters(const FhgRegisters&) = delete;  // the hooks and the status point into this one
    FhgRegisters& operator=(const FhgRegisters&) = delete;

    bool access(uint32_t offset, uint32_t& value, bool write);
    FrameStatus& status() { return status_; }
    const FrameStatus& status() const { return status_; }

    // LocMaxFinder's candidates, in order; returns how many were dropped on a full FIFO.
    unsigned push(const std::vector<fhg::Candidate>& candidates);
    unsigned fifo_level() const { return unsigned(fifo_.size()); }
    // Fault injection (fifo_overflow): every candidate is dropped as if the FIFO were full,
    // until the next START or RESET.
    void refuse_candidates() { refusing_ = true; }
    bool irq() const;

private:
    void command(uint32_t ctrl);
    bool fifo_irq() const;
    uint32_t pop();

    RegisterBank bank_;
    FrameStatus status_;
    Limits limits_;
    Hooks hooks_;
    std::deque<uint32_t> fifo_;
    bool refusing_ = false;
};

}  // namespace surfvp
