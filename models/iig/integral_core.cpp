#include "integral_core.h"

#include <cstring>
#include <emmintrin.h>
#include <stdexcept>

namespace surfvp {

IntegralCore::IntegralCore(unsigned sum_bits) : sum_bits_(sum_bits), limit_(uint64_t(1) << sum_bits) {
    if (sum_bits < 8 || sum_bits > 32)
        throw std::invalid_argument("integral sum width must be 8 to 32 bits, not " + std::to_string(sum_bits));
}

namespace {

// The sum of a row's pixels, 16 at a time.
uint64_t pixel_sum(const uint8_t* pixels, int width) {
    __m128i sums = _mm_setzero_si128();
    int x = 0;
    for (; x + 16 <= width; x += 16)
        sums = _mm_add_epi64(
            sums, _mm_sad_epu8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(pixels + x)), _mm_setzero_si128()));
    uint64_t total = uint64_t(_mm_cvtsi128_si64(sums)) + uint64_t(_mm_cvtsi128_si64(_mm_unpackhi_epi64(sums, sums)));
    for (; x < width; ++x) total += pixels[x];
    return total;
}

// Running sums of four pixels at a time (each lane its prefix within the four, plus the run
// before them), the row above added; every sum fits 32 bits.
void row_fitting(const uint8_t* pixels, const uint32_t* above, uint32_t* out, int width) {
    const __m128i zero = _mm_setzero_si128();
    __m128i run = zero;  // the sum so far, in every lane
    int x = 0;
    for (; x + 4 <= width; x += 4) {
        int32_t four;
        std::memcpy(&four, pixels + x, 4);
        __m128i v = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(four), zero), zero);
        v = _mm_add_epi32(v, _mm_slli_si128(v, 4));
        v = _mm_add_epi32(v, _mm_slli_si128(v, 8));
        v = _mm_add_epi32(v, run);
        run = _mm_shuffle_epi32(v, _MM_SHUFFLE(3, 3, 3, 3));
        if (above) v = _mm_add_epi32(v, _mm_loadu_si128(reinterpret_cast<const __m128i*>(above + x)));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x), v);
    }
    uint32_t last = uint32_t(_mm_cvtsi128_si32(run));
    for (; x < width; ++x) {
        last += pixels[x];
        out[x] = last + (above ? above[x] : 0);
    }
}

}  // namespace

bool IntegralCore::row(const uint8_t* pixels, const uint32_t* above, uint32_t* out, int width) const {
    // The row's values rise along it (pixels are not negative, and the row above, a row of the
    // same image, rises too), so its last is its largest: when that fits, every sum does and
    // they go four at a time.
    if (width > 0 && pixel_sum(pixels, width) + (above ? above[width - 1] : 0) < limit_) {
        row_fitting(pixels, above, out, width);
        return true;
    }
    // A running sum along the row plus the row above: what a 1 pixel/clock adder chain does,
    // stopping at the first value that does not fit.
    uint64_t run = 0;
    for (int x = 0; x < width; ++x) {
        run += pixels[x];
        const uint64_t value = run + (above ? above[x] : 0);
        if (value >= limit_) return false;
        out[x] = static_cast<uint32_t>(value);
    }
    return true;
}

bool IntegralCore::fits(const uint8_t* pixels, int width, int height, size_t stride) const {
    uint64_t total = 0;
    for (int y = 0; y < height; ++y) total += pixel_sum(pixels + size_t(y) * stride, width);
    return total < limit_;
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
