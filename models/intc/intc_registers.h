#pragma once
// The XPS INTC's register behaviour (the table in intc_regs.h). Inputs are level sensitive
// and active high: while an input is high and MER.HIE is set, its ISR bit is set, and
// acknowledging it (IAR) while the input is still high sets it again. The output is
// MER.ME && (ISR & IER) != 0. Plain C++: the SystemC model and direct mode both own one and
// give it the input levels (`levels`), so both latch, mask and acknowledge alike.
#include <cstdint>
#include <functional>

#include "intc_regs.h"
#include "models/common/register_bank.h"

namespace surfvp {

class IntcRegisters {
public:
    // `levels`: the inputs now, one bit each; `changed`: after a write, the output may change.
    IntcRegisters(unsigned inputs, std::function<uint32_t()> levels, std::function<void()> changed = {});
    IntcRegisters(const IntcRegisters&) = delete;
    IntcRegisters& operator=(const IntcRegisters&) = delete;

    bool access(uint32_t offset, uint32_t& value, bool write);
    void latch();         // ISR |= the high inputs (while MER.HIE)
    bool output() const;  // the line to the CPU, as of the last latch
    uint32_t pending() const { return isr() & bank_.value(intc::IER); }

private:
    uint32_t isr() const { return bank_.value(intc::ISR); }

    RegisterBank bank_;
    uint32_t valid_;  // one bit per input that exists
    std::function<uint32_t()> levels_;
    std::function<void()> changed_;
};

}  // namespace surfvp
