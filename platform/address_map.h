#pragma once
// The SoC's address map and interrupt lines (paper Fig. 3), named once: the platform wires
// the bus decoders from it and the software includes it. Byte order is big-endian
// throughout: see models/common/byte_order.h.
//
//   PLB1 (CPU's MPLB; register slaves):  DDR, INTC, test DMA, IIG and FHG registers
//   PLB2 (DMA traffic, "increased capacity"): DDR only
#include <cstdint>

namespace surfvp::map {

struct Region {
    const char* name;
    uint32_t base;
    uint32_t size;
};

// DDR is at 0 on both buses; the window is 256 MiB (the ML507's DDR2), the installed
// size is the memory.size parameter.
constexpr Region ddr{"ddr", 0x0000'0000, 0x1000'0000};
// The XPS INTC at EDK's default base.
constexpr Region intc{"intc", 0x8180'0000, 0x0001'0000};
// The standalone memory-to-memory DMA (smoke scenario's test master).
constexpr Region dma{"dma", 0xC000'0000, 0x0001'0000};
// The SSA IIG and SSA FHG register windows.
constexpr Region iig{"iig", 0xC100'0000, 0x0001'0000};
constexpr Region fhg{"fhg", 0xC200'0000, 0x0001'0000};

// Accelerator pair k (libSSA2 drives several): its windows are k strides above pair 0's.
constexpr uint32_t kAcceleratorStride = 0x0010'0000;
constexpr unsigned kMaxAccelerators = 8;
constexpr uint32_t iig_base(unsigned k) { return iig.base + k * kAcceleratorStride; }
constexpr uint32_t fhg_base(unsigned k) { return fhg.base + k * kAcceleratorStride; }

// Interrupt controller inputs (bit numbers in the INTC registers; lower is higher priority).
namespace irq {
constexpr unsigned dma = 0;
constexpr unsigned iig(unsigned k) { return 1 + 2 * k; }
constexpr unsigned fhg(unsigned k) { return 2 + 2 * k; }
}  // namespace irq

}  // namespace surfvp::map
