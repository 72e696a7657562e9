#pragma once
// Integral image (paper §II, eq. 1) and the box sums every later SURF step is built from.
//
//   I(x, y) = sum of pixel(i, j) for i <= x, j <= y      (inclusive, no zero row or column)
//
// Values are uint32. Box sums are formed with unsigned wrap-around arithmetic, so a box sum is
// exact whenever the true sum fits in 32 bits (any box of up to 16.8 M pixels of value 255),
// even if the corner values themselves have wrapped on a very large image.
//
// Reads outside the image follow OpenSURF's rule: a coordinate < 0 reads 0 (the empty sum), a
// coordinate beyond the last column/row is clamped to it. The effect is that a box sum counts
// only the pixels of the box that lie inside the image, i.e. the image is zero-padded.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cv {
class Mat;  // only IntegralImage::compute needs OpenCV; the views compile without it (the PPC440 build)
}

namespace surfvp::surf {

// Every integral-image view offers the same four things, so the SURF steps that read the
// integral image (box sums, Haar wavelets, orientation, descriptor, hessian_at) are templates
// over the view type and run unchanged on
//   - IntegralView (below): native uint32 values in host memory, the reference's own;
//   - MemoryView (memory_view.h): big-endian words in simulated DDR, each read reported to a
//     probe, so the software stage's reads can be costed (sw/cpu_cost).
// A view type V provides
//   int width, height;
//   uint32_t V::at(int x, int y) const;       // I(x, y), unchecked
//   uint32_t V::clamped(int x, int y) const;  // the clamp rule, through clamped_read()

// I(x, y) with OpenSURF's clamp: negative -> 0 (no read), beyond the last column/row -> clamped.
// One definition shared by every view type so that they all read the same elements.
template <class View>
uint32_t clamped_read(const View& ii, int x, int y) {
    if (x < 0 || y < 0) return 0;
    return ii.at(x < ii.width ? x : ii.width - 1, y < ii.height ? y : ii.height - 1);
}

// A non-owning view of a native integral image.
struct IntegralView {
    const uint32_t* data = nullptr;
    int width = 0;
    int height = 0;
    size_t stride = 0;  // elements (not bytes) from one row to the next

    uint32_t at(int x, int y) const { return data[static_cast<size_t>(y) * stride + x]; }
    uint32_t clamped(int x, int y) const { return clamped_read(*this, x, y); }
};

// Owns the values; build one from an 8-bit grey image.
class IntegralImage {
public:
    IntegralImage() = default;
    explicit IntegralImage(const cv::Mat& gray8) { compute(gray8); }  // CV_8UC1, any size

    // Recomputes from `gray8`, reusing the storage when the size allows (one allocation per
    // stream of frames rather than per frame).
    void compute(const cv::Mat& gray8);

    IntegralView view() const { return {values_.data(), width_, height_, stride_}; }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    std::vector<uint32_t> values_;
    int width_ = 0;
    int height_ = 0;
    size_t stride_ = 0;
};

// Sum of the pixels in columns [x0, x1] and rows [y0, y1] (inclusive), unchecked: the caller
// guarantees every read is inside, i.e. x0 >= 1, y0 >= 1, x1 < width, y1 < height.
template <class View>
int32_t box_sum_inside(const View& ii, int x0, int y0, int x1, int y1) {
    const uint32_t s = ii.at(x1, y1) - ii.at(x0 - 1, y1) - ii.at(x1, y0 - 1) + ii.at(x0 - 1, y0 - 1);
    return static_cast<int32_t>(s);
}

// Same sum with the clamp rule: any box, pixels outside the image count as 0. An empty box
// (x1 < x0 or y1 < y0) sums to 0.
template <class View>
int64_t box_sum(const View& ii, int x0, int y0, int x1, int y1) {
    if (x1 < x0 || y1 < y0) return 0;
    const uint32_t s =
        ii.clamped(x1, y1) - ii.clamped(x0 - 1, y1) - ii.clamped(x1, y0 - 1) + ii.clamped(x0 - 1, y0 - 1);
    return static_cast<int64_t>(s);
}

}  // namespace surfvp::surf
