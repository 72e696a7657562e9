#pragma once
// An integral-image view over raw memory as the PPC440 sees it (docs/architecture.md#principles, 9: memory is
// big-endian, 32-bit words in address order). The IIG leaves the integral image in DDR as
// 32-bit big-endian words, row-major, `stride` bytes per row (models/iig); the software stage
// runs the reference's orientation, descriptor and hessian_at on it through this view.
//
// Every 32-bit read calls probe.load(bus address, 4) before converting the word, so a probe
// can count the reads and replay their addresses into a cache model (sw/cpu_cost). The probe
// is a template parameter held by value: a small copyable handle whose
//   void load(uint32_t address, unsigned bytes) const
// is inlined. NoProbe costs nothing; the native IntegralView has no probe at all.
#include <cstddef>
#include <cstdint>

#include "models/common/byte_order.h"
#include "sw/surf/integral_image.h"

namespace surfvp::surf {

struct NoProbe {
    void load(uint32_t /*address*/, unsigned /*bytes*/) const {}
};

template <class Probe = NoProbe>
struct MemoryView {
    const uint8_t* bytes = nullptr;  // the byte at `address`
    uint32_t address = 0;            // bus address of bytes[0]
    int width = 0;
    int height = 0;
    size_t stride = 0;  // bytes (not elements) from one row to the next
    Probe probe{};

    uint32_t at(int x, int y) const {
        const size_t offset = static_cast<size_t>(y) * stride + static_cast<size_t>(x) * 4;
        probe.load(address + static_cast<uint32_t>(offset), 4);
        return load_be32(bytes + offset);
    }
    uint32_t clamped(int x, int y) const { return clamped_read(*this, x, y); }
};

}  // namespace surfvp::surf
