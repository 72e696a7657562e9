#include "fhg_registers.h"

#include <stdexcept>

static_assert(surfvp::fhg_regs::STATUS_BUSY == surfvp::FrameStatus::kBusy &&
              surfvp::fhg_regs::STATUS_DONE == surfvp::FrameStatus::kDone &&
              surfvp::fhg_regs::STATUS_ERROR == surfvp::FrameStatus::kError);

namespace surfvp {
namespace r = fhg_regs;

FhgRegisters::FhgRegisters(const Limits& limits, Hooks hooks)
    : bank_(r::table()),
      status_(bank_.value(r::STATUS), bank_.value(r::ERROR_CODE)),
      limits_(limits),
      hooks_(std::move(hooks)) {
    if (limits.fifo_depth == 0) throw std::invalid_argument("the maxima FIFO needs a depth above zero");
    bank_.value(r::DET_FRAC_BITS) = limits.det_frac_bits;
    bank_.value(r::DET_BYTES) = limits.det_bytes;
    bank_.on_write(r::CTRL, [this](uint32_t ctrl) { command(ctrl); });
    bank_.on_read(r::STATUS, [this] { return status_.bits() | (fifo_irq() ? r::STATUS_FIFO_IRQ : 0); });
    bank_.on_read(r::FIFO_DATA, [this] { return pop(); });
    bank_.on_read(r::FIFO_LEVEL, [this] { return fifo_level(); });
}

bool FhgRegisters::access(uint32_t offset, uint32_t& value, bool write) {
    if (!bank_.access(offset, value, write)) return false;
    if ((write || offset == r::FIFO_DATA) && hooks_.changed) hooks_.changed();
    return true;
}

void FhgRegisters::command(uint32_t ctrl) {
    if (ctrl & r::CTRL_RESET) {
        if (hooks_.reset) hooks_.reset();
        if (!status_.busy()) {
            status_.reset();
            fifo_.clear();
            refusing_ = false;
        }
        return;
    }
    if (ctrl & r::CTRL_ABORT) {
        if (status_.busy() && hooks_.abort) hooks_.abort();
        return;
    }
    if (!(ctrl & r::CTRL_START)) return;
    if (status_.busy()) return status_.flag(r::ERR_START_BUSY);
    const uint32_t width = bank_.value(r::WIDTH), height = bank_.value(r::HEIGHT);
    if (width == 0 || height == 0 || width > limits_.max_width || height > limits_.max_height)
        return status_.flag(r::ERR_SIZE);
    fifo_.clear();
    refusing_ = false;
    bank_.value(r::OVERFLOW_COUNT) = bank_.value(r::CANDIDATES) = 0;
    status_.start();
    hooks_.start({bank_.value(r::DET_ADDR), width, height, int32_t(bank_.value(r::THRESHOLD))});
}

unsigned FhgRegisters::push(const std::vector<fhg::Candidate>& candidates) {
    unsigned dropped = 0;
    for (const fhg::Candidate& c : candidates) {
        ++bank_.value(r::CANDIDATES);
        if (fifo_.size() < limits_.fifo_depth && !refusing_) {
            fifo_.push_back(fhg::pack_candidate(c));
            continue;
        }
        ++dropped;
        ++bank_.value(r::OVERFLOW_COUNT);
        status_.set(r::STATUS_FIFO_OVERFLOW);
    }
    return dropped;
}

uint32_t FhgRegisters::pop() {
    if (fifo_.empty()) return 0;  // bit 31 clear: nothing was there
    const uint32_t word = fifo_.front();
    fifo_.pop_front();
    return word;
}

bool FhgRegisters::fifo_irq() const {
    const uint32_t threshold = bank_.value(r::FIFO_THRESHOLD);
    return threshold && fifo_.size() >= threshold;
}

bool FhgRegisters::irq() const {
    const uint32_t ctrl = bank_.value(r::CTRL);
    return ((ctrl & r::CTRL_IRQ_EN_DONE) && status_.finished()) || ((ctrl & r::CTRL_IRQ_EN_FIFO) && fifo_irq());
}

}  // namespace surfvp
