#pragma once
// XPS INTC register map (Xilinx xps_intc; PLATFORM_FACTS §2): the contract between the
// interrupt controller model and the software. Registers are 32-bit, big-endian on the bus.
#include <cstdint>

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

}  // namespace surfvp::intc
