#pragma once
// The co-simulation of the verilated FHG datapath against HessianCore: test_rtl's at the
// model's defaults, test_rtl_narrow's at a precision that saturates. Each executable links one
// verilated build (models/fhg/rtl/rtl_datapath.cpp with its own Vfhg_datapath).
#include <gtest/gtest.h>

#include <array>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "models/fhg/hessian_core.h"
#include "models/fhg/rtl/rtl_datapath.h"
#include "models/fhg/sequence_memory.h"
#include "test_images.h"

namespace surfvp::fhg {

using Crop = test::Integral;

// The integral image of a 256 x 192 crop from the middle of an image.
inline Crop crop_of(const cv::Mat& image) {
    return test::integral_of(image(cv::Rect((image.cols - 256) / 2, (image.rows - 192) / 2, 256, 192)).clone());
}

inline cv::Mat castle_frame() {
    const std::string path = std::string(VISP_DATA_DIR) + "/mbt-depth/Castle-simu/Images/Image_0001.pgm";
    cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (image.empty()) ADD_FAILURE() << path << " is missing: install the Debian package visp-images-data";
    return image;
}

struct CoSimulation {
    uint64_t blocks = 0, determinants = 0, mismatches = 0, nonzero = 0;
    std::string first_mismatch;
    std::vector<uint64_t> block_cycles;  // between consecutive blocks' first determinants
    bool overrun = false;
};

// Runs the whole crop through the RTL with this sequence image and compares every determinant
// with HessianCore's at `precision` (the build's).
inline CoSimulation co_simulate(const Crop& crop, const SequenceImage& image, const SequenceParams& p,
                                const Precision& precision = {}, bool stop_at_mismatch = false) {
    const HessianCore core{precision};
    RtlDatapath rtl(precision, p, 1024, image);
    rtl.start(crop.view.width, crop.view.height);
    // The PixelBus has the whole crop: the FIFO takes its values one a cycle while it has room.
    const size_t values = size_t(crop.view.width) * size_t(crop.view.height);
    CoSimulation out;
    std::array<int32_t, kDeterminantsPerBlock> expected{};
    const uint64_t total = uint64_t((crop.view.width + 1) / 2) * uint64_t((crop.view.height + 1) / 2);
    uint64_t last_first = 0;
    while (out.determinants < total * kDeterminantsPerBlock && rtl.cycles() < 200 * total + 1000) {
        if (stop_at_mismatch && out.mismatches) break;
        const RtlDatapath::Determinant d = rtl.step(crop.view, values);
        if (!d.valid) continue;
        if (d.index == 0) {
            expected = core.block(crop.view, d.block_x, d.block_y);
            if (out.blocks++) out.block_cycles.push_back(rtl.cycles() - last_first);
            last_first = rtl.cycles();
        }
        ++out.determinants;
        out.nonzero += expected[size_t(d.index)] != 0;
        if (d.value != expected[size_t(d.index)] && out.mismatches++ == 0)
            out.first_mismatch = "block (" + std::to_string(d.block_x) + ", " + std::to_string(d.block_y) +
                                 ") determinant " + std::to_string(d.index) + ": RTL " + std::to_string(d.value) +
                                 ", HessianCore " + std::to_string(expected[size_t(d.index)]);
    }
    out.overrun = rtl.overrun();
    return out;
}

}  // namespace surfvp::fhg
