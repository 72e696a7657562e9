#include "integral_core.h"

#include <stdexcept>

namespace surfvp {

IntegralCore::IntegralCore(unsigned sum_bits) : sum_bits_(sum_bits), limit_(uint64_t(1) << sum_bits) {
    if (sum_bits < 8 || sum_bits > 32)
        throw std::invalid_argument("integral sum width must be 8 to 32 bits, not " + std::to_string(sum_bits));
}

bool IntegralCore::row(const uint8_t* pixels, const uint32_t* above, uint32_t* out, int width) const {
    // A running sum along the row plus the row above: what a 1 pixel/clock adder chain does.
    uint64_t run = 0;
    for (int x = 0; x < width; ++x) {
        run += pixels[x];
        const uint64_t value = run + (above ? above[x] : 0);
        if (value >= limit_) return false;
        out[x] = static_cast<uint32_t>(value);
    }
    return true;
}

std::optional<std::vector<uint32_t>> IntegralCore::image(const uint8_t* pixels, int width, int height,
                                                         size_t stride) const {
    std::vector<uint32_t> out(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y) {
        const uint32_t* above = y ? out.data() + size_t(y - 1) * width : nullptr;
        if (!row(pixels + size_t(y) * stride, above, out.data() + size_t(y) * width, width)) return std::nullopt;
    }
    return out;
}

}  // namespace surfvp
