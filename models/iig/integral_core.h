#pragma once
// SSA IIG's arithmetic (paper §III-B, eq. 1): the integral image of an 8-bit grey image,
// I(x, y) = sum of pixels (i <= x, j <= y). It is the paper's inclusive definition: no zero
// row or column, so I equals cv::integral's result without its first row and column.
// Values are kept in `sum_bits` significant bits of a 32-bit word (28 suffice for a
// 1024 x 1024 white image: 255 x 2^20 < 2^28); an image whose total would not fit is an
// error, never a silent wrap. Plain C++, no SystemC.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace surfvp {

// A read-only view of an inclusive integral image (row-major, `stride` values per row).
struct IntegralView {
    const uint32_t* data = nullptr;
    int width = 0;
    int height = 0;
    size_t stride = 0;

    const uint32_t* row(int y) const { return data + size_t(y) * stride; }
    uint32_t at(int x, int y) const { return data[size_t(y) * stride + size_t(x)]; }
};

class IntegralCore {
public:
    explicit IntegralCore(unsigned sum_bits);

    // One row: `pixels` (width bytes) added to the row above (`above`, this image's row before,
    // nullptr for row 0).
    // Returns false (and leaves `out` partial) if a value exceeds sum_bits.
    bool row(const uint8_t* pixels, const uint32_t* above, uint32_t* out, int width) const;

    // Whether every sum of an image (`stride` bytes per row) fits sum_bits: its last, the sum of
    // all its pixels, is its largest.
    bool fits(const uint8_t* pixels, int width, int height, size_t stride) const;

    // A whole image (`stride` bytes per row); empty when the sums overflow `sum_bits`.
    std::optional<std::vector<uint32_t>> image(const uint8_t* pixels, int width, int height, size_t stride) const;

    unsigned sum_bits() const { return sum_bits_; }
    uint64_t limit() const { return limit_; }  // the first value that does not fit

private:
    unsigned sum_bits_;
    uint64_t limit_;
};

}  // namespace surfvp
