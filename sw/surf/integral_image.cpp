#include "sw/surf/integral_image.h"

#include <stdexcept>

#include <opencv2/core/mat.hpp>

namespace surfvp::surf {

void IntegralImage::compute(const cv::Mat& gray8) {
    if (gray8.type() != CV_8UC1) throw std::invalid_argument("IntegralImage needs a CV_8UC1 image");
    width_ = gray8.cols;
    height_ = gray8.rows;
    stride_ = static_cast<size_t>(gray8.cols);
    values_.resize(stride_ * static_cast<size_t>(height_));
    // Row y = row y-1 + running sum of pixel row y (eq. 1 computed incrementally).
    for (int y = 0; y < height_; ++y) {
        const uint8_t* pixels = gray8.ptr<uint8_t>(y);
        uint32_t* out = values_.data() + static_cast<size_t>(y) * stride_;
        const uint32_t* above = y > 0 ? out - stride_ : nullptr;
        uint32_t row_sum = 0;
        for (int x = 0; x < width_; ++x) {
            row_sum += pixels[x];
            out[x] = row_sum + (above ? above[x] : 0u);
        }
    }
}

}  // namespace surfvp::surf
