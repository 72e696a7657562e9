#pragma once
// Real and synthetic images for the IP-block tests. Real ones come from Debian's opencv-doc;
// a missing file fails the test with the package to install, never skips it.
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>
#include <vector>

#include "models/iig/integral_core.h"

namespace surfvp::test {

inline cv::Mat real_image(const std::string& name) {
    const std::string path = std::string(OPENCV_DATA_DIR) + "/" + name;
    cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (image.empty()) ADD_FAILURE() << path << " is missing: install the Debian package opencv-doc";
    return image;
}

// graf1 resized to the chip's budget size.
inline cv::Mat graf_1024x768() {
    cv::Mat image = real_image("graf1.png"), out;
    if (image.empty()) return image;
    cv::resize(image, out, cv::Size(1024, 768), 0, 0, cv::INTER_AREA);
    return out;
}

// An image's integral image as the IIG computes it (inclusive, 32-bit), with its view.
struct Integral {
    std::vector<uint32_t> values;
    IntegralView view;
};

inline Integral integral_of(const cv::Mat& image) {
    Integral ii{*IntegralCore(32).image(image.data, image.cols, image.rows, image.step), {}};
    ii.view = {ii.values.data(), image.cols, image.rows, size_t(image.cols)};
    return ii;
}

inline cv::Mat random_image(int width, int height, unsigned seed) {
    cv::Mat image(height, width, CV_8UC1);
    std::mt19937 rng(seed);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.at<uint8_t>(y, x) = uint8_t(rng());
    return image;
}

}  // namespace surfvp::test
