#pragma once
// One frame as the hardware leaves it in DDR, built with the hardware's own cores (no
// SystemC): the IIG's integral image, the FHG's determinant records and its maxima-FIFO words,
// serialised big-endian as the DMA writes them (models/common/byte_order.h, fhg_regs.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "models/common/byte_order.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/hessian_core.h"
#include "models/fhg/local_max_finder.h"
#include "models/iig/integral_core.h"
#include "sw/stage/software_stage.h"

namespace surfvp::stage_test {

// graf1 (Debian package opencv-doc) at the chip's 1024x768, as the other suites use it;
// an empty Mat and a failure naming the package when it is missing.
inline cv::Mat graf1_1024x768() {
    const std::string path = std::string(OPENCV_DATA_DIR) + "/graf1.png";
    if (!std::filesystem::exists(path)) {
        ADD_FAILURE() << path << " is missing: install the Debian package opencv-doc "
                      << "(apt-get install opencv-doc), which ships OpenCV's example data";
        return {};
    }
    const cv::Mat gray = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (gray.empty()) {
        ADD_FAILURE() << path << " cannot be decoded (package opencv-doc)";
        return {};
    }
    cv::Mat resized;
    cv::resize(gray, resized, cv::Size(1024, 768), 0, 0, cv::INTER_AREA);
    return resized;
}

constexpr uint32_t kIntegralAddress = 0x01000000;     // arbitrary DDR addresses of the task's
constexpr uint32_t kDeterminantAddress = 0x02000000;  // buffers (line-aligned, as a driver would)

struct HardwareFrame {
    int width = 0, height = 0;
    size_t stride = 0;                  // integral image, bytes per row
    std::vector<uint32_t> integral;     // native values, for the reference views
    std::vector<uint8_t> integral_be;   // as in DDR
    std::vector<uint8_t> determinants;  // as in DDR
    std::vector<uint32_t> fifo;         // maxima-FIFO words in the order the FHG pushes them
    unsigned det_frac_bits = 0;
    unsigned det_bytes = 4;

    sw::FrameBuffers buffers() const {
        sw::FrameBuffers b;
        b.integral = integral_be.data();
        b.integral_address = kIntegralAddress;
        b.integral_stride = stride;
        b.determinants = determinants.data();
        b.determinants_address = kDeterminantAddress;
        b.width = width;
        b.height = height;
        b.det_frac_bits = det_frac_bits;
        b.det_bytes = det_bytes;
        return b;
    }
};

// IIG (28-bit sums) and FHG (`precision`) on `gray`; the FHG's threshold register holds
// `threshold` (float units) in its fixed point, as the driver would program it.
inline HardwareFrame run_hardware(const cv::Mat& gray, float threshold, const fhg::Precision& precision = {}) {
    HardwareFrame f;
    f.width = gray.cols;
    f.height = gray.rows;
    f.stride = size_t(f.width) * 4;
    const auto values = IntegralCore(28).image(gray.data, gray.cols, gray.rows, gray.step);
    if (!values) {
        ADD_FAILURE() << "integral image overflows 28 bits";
        return f;
    }
    f.integral = *values;
    f.integral_be.resize(f.integral.size() * 4);
    for (size_t i = 0; i < f.integral.size(); ++i) store_be32(&f.integral_be[i * 4], f.integral[i]);

    const IntegralView view{f.integral.data(), f.width, f.height, size_t(f.width)};
    const fhg::HessianCore core{precision};
    f.det_frac_bits = core.precision().det_frac_bits;
    f.det_bytes = fhg_regs::det_bytes_for(precision.det_bits);
    const uint32_t record = fhg_regs::record_bytes(f.det_bytes);
    const fhg::LocalMaxFinder finder(core.from_float(threshold));
    const int blocks = (f.width + 1) / 2, block_rows = (f.height + 1) / 2;
    f.determinants.resize(size_t(blocks) * block_rows * record);
    std::vector<int32_t> row(size_t(blocks) * fhg::kDeterminantsPerBlock);
    std::vector<fhg::Candidate> candidates;
    for (int by = 0; by < block_rows; ++by) {
        core.block_row(view, by, row.data());
        uint8_t* out = &f.determinants[size_t(by) * blocks * record];
        for (size_t i = 0; i < row.size(); ++i) fhg_regs::store_det(out + i * f.det_bytes, row[i], f.det_bytes);
        finder.block_row(row.data(), blocks, by, candidates);
    }
    for (const fhg::Candidate& c : candidates) f.fifo.push_back(fhg::pack_candidate(c));
    return f;
}

}  // namespace surfvp::stage_test
