#include "intc_registers.h"

#include <stdexcept>
#include <string>

namespace surfvp {

IntcRegisters::IntcRegisters(unsigned inputs, std::function<uint32_t()> levels, std::function<void()> changed)
    : bank_(intc::table()),
      valid_(inputs >= 32 ? ~0u : (1u << inputs) - 1),
      levels_(std::move(levels)),
      changed_(std::move(changed)) {
    if (inputs == 0 || inputs > 32)
        throw std::invalid_argument("the XPS INTC has 1 to 32 inputs, not " + std::to_string(inputs));
    bank_.on_read(intc::IPR, [this] { return pending(); });
    bank_.on_read(intc::IVR, [this] { return pending() ? uint32_t(__builtin_ctz(pending())) : intc::kNoVector; });
    bank_.on_write(intc::ISR, [this](uint32_t) { bank_.value(intc::ISR) &= valid_; });
    bank_.on_write(intc::IER, [this](uint32_t) { bank_.value(intc::IER) &= valid_; });
    bank_.on_write(intc::IAR, [this](uint32_t v) { bank_.value(intc::ISR) &= ~v; });
    bank_.on_write(intc::SIE, [this](uint32_t v) { bank_.value(intc::IER) |= v & valid_; });
    bank_.on_write(intc::CIE, [this](uint32_t v) { bank_.value(intc::IER) &= ~v; });
}

bool IntcRegisters::access(uint32_t offset, uint32_t& value, bool write) {
    latch();
    const uint32_t mer = bank_.value(intc::MER);
    if (write && offset == intc::ISR && (mer & intc::MER_HIE)) return true;  // ISR is software's only before HIE
    if (write && offset == intc::MER) value |= mer & intc::MER_HIE;          // HIE is write-once
    if (!bank_.access(offset, value, write)) return false;
    if (!write) return true;
    latch();  // an acknowledged input that is still high is pending again at once
    if (changed_) changed_();
    return true;
}

void IntcRegisters::latch() {
    if (bank_.value(intc::MER) & intc::MER_HIE) bank_.value(intc::ISR) |= levels_() & valid_;
}

bool IntcRegisters::output() const { return (bank_.value(intc::MER) & intc::MER_ME) && pending() != 0; }

}  // namespace surfvp
