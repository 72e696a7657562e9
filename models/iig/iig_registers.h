#pragma once
// The SSA IIG's register behaviour (the table in iig_regs.h): what a START, an ABORT and a
// STATUS write do, and when the interrupt line is high. Plain C++: the SystemC model and
// direct mode both own one and answer the driver through it, and supply what a frame does.
#include <cstdint>
#include <functional>

#include "iig_regs.h"
#include "models/common/frame_status.h"
#include "models/common/register_bank.h"

namespace surfvp {

class IigRegisters {
public:
    struct Limits {
        unsigned max_width = 1024, max_height = 1024;
    };
    // The frame's registers as START latched them (strides of 0 resolved).
    struct Frame {
        uint32_t src, dst, width, height, src_stride, dst_stride;
        bool stream;
    };
    using Hooks = FrameHooks<Frame>;

    IigRegisters(const Limits& limits, Hooks hooks);
    IigRegisters(const IigRegisters&) = delete;  // the hooks and the status point into this one
    IigRegisters& operator=(const IigRegisters&) = delete;

    bool access(uint32_t offset, uint32_t& value, bool write);
    FrameStatus& status() { return status_; }
    const FrameStatus& status() const { return status_; }
    // The frame has ended: DONE, or ERROR with `code`; STALL_CYCLES says how long it waited.
    void end(bool failed, uint32_t code, uint32_t stall_cycles);
    bool irq() const { return (bank_.value(iig::CTRL) & iig::CTRL_IRQ_EN) && status_.finished(); }

private:
    void command(uint32_t ctrl);

    RegisterBank bank_;
    FrameStatus status_;
    Limits limits_;
    Hooks hooks_;
};

}  // namespace surfvp
