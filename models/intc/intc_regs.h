#pragma once
// XPS INTC register map (Xilinx xps_intc; docs/sources.md#intc-and-dma): the contract between the
// interrupt controller model and the software. Registers are 32-bit, big-endian on the bus.
#include <cstdint>

#include "models/common/register_bank.h"

namespace surfvp::intc {

constexpr uint32_t ISR = 0x00;  // status: one bit per input, latched (write only while MER.HIE = 0)
constexpr uint32_t IPR = 0x04;  // pending: ISR & IER (read only)
constexpr uint32_t IER = 0x08;  // enable
constexpr uint32_t IAR = 0x0C;  // acknowledge: writing 1 clears the ISR bit (write only)
constexpr uint32_t SIE = 0x10;  // set enable bits (write only)
constexpr uint32_t CIE = 0x14;  // clear enable bits (write only)
constexpr uint32_t IVR = 0x18;  // lowest pending input number, or kNoVector (read only)
constexpr uint32_t MER = 0x1C;  // master enable

constexpr uint32_t MER_ME = 1u << 0;   // drive the output line
constexpr uint32_t MER_HIE = 1u << 1;  // hardware inputs enabled (write-once: cannot be cleared)
constexpr uint32_t kNoVector = 0xFFFFFFFFu;

// The same registers as a table: the model and direct mode behave by it (IntcRegisters),
// docs/registers.md is generated from it.
inline const RegisterTable& table() {
    static const RegisterTable t{
        "XPS INTC",
        "Level-sensitive inputs, one bit per input (docs/architecture.md lists the lines), one output to the CPU.",
        {{"ISR",
          ISR,
          Access::RW,
          0,
          "status: an input's bit is set while the input is high (MER.HIE); writable only while MER.HIE = 0",
          {}},
         {"IPR", IPR, Access::RO, 0, "pending: ISR & IER", {}},
         {"IER", IER, Access::RW, 0, "enable, one bit per input", {}},
         {"IAR",
          IAR,
          Access::WO,
          0,
          "acknowledge: writing 1 clears the ISR bit (set again at once while the input is high)",
          {}},
         {"SIE", SIE, Access::WO, 0, "writing 1 sets the IER bit", {}},
         {"CIE", CIE, Access::WO, 0, "writing 1 clears the IER bit", {}},
         {"IVR", IVR, Access::RO, kNoVector, "lowest pending input number, or 0xFFFFFFFF when none is pending", {}},
         {"MER",
          MER,
          Access::RW,
          0,
          "master enable",
          {{"ME", 0, 1, Access::RW, "drive the output line"},
           {"HIE", 1, 1, Access::RW, "hardware inputs enabled; write-once: cannot be cleared"}}}}};
    return t;
}

}  // namespace surfvp::intc
