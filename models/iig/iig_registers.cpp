#include "iig_registers.h"

static_assert(surfvp::iig::STATUS_BUSY == surfvp::FrameStatus::kBusy &&
              surfvp::iig::STATUS_DONE == surfvp::FrameStatus::kDone &&
              surfvp::iig::STATUS_ERROR == surfvp::FrameStatus::kError);

namespace surfvp {

IigRegisters::IigRegisters(const Limits& limits, Hooks hooks)
    : bank_(iig::table()),
      status_(bank_.value(iig::STATUS), bank_.value(iig::ERROR_CODE)),
      limits_(limits),
      hooks_(std::move(hooks)) {
    bank_.on_write(iig::CTRL, [this](uint32_t ctrl) { command(ctrl); });
}

bool IigRegisters::access(uint32_t offset, uint32_t& value, bool write) {
    if (!bank_.access(offset, value, write)) return false;
    if (write && hooks_.changed) hooks_.changed();
    return true;
}

void IigRegisters::command(uint32_t ctrl) {
    if (ctrl & iig::CTRL_RESET) {
        if (hooks_.reset) hooks_.reset();
        if (!status_.busy()) status_.reset();
        return;
    }
    if (ctrl & iig::CTRL_ABORT) {
        if (status_.busy() && hooks_.abort) hooks_.abort();
        return;
    }
    if (!(ctrl & iig::CTRL_START)) return;
    if (status_.busy()) return status_.flag(iig::ERR_START_BUSY);
    const uint32_t width = bank_.value(iig::WIDTH), height = bank_.value(iig::HEIGHT);
    if (width == 0 || height == 0 || width > limits_.max_width || height > limits_.max_height)
        return status_.flag(iig::ERR_SIZE);
    const uint32_t src_stride = bank_.value(iig::SRC_STRIDE), dst_stride = bank_.value(iig::DST_STRIDE);
    const Frame frame{bank_.value(iig::SRC),
                      bank_.value(iig::DST),
                      width,
                      height,
                      src_stride ? src_stride : width,
                      dst_stride ? dst_stride : 4 * width,
                      (ctrl & iig::CTRL_STREAM) != 0};
    status_.start();
    hooks_.start(frame);
}

void IigRegisters::end(bool failed, uint32_t code, uint32_t stall_cycles) {
    bank_.value(iig::STALL_CYCLES) = stall_cycles;
    status_.end(failed, code);
}

}  // namespace surfvp
