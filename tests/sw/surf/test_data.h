#pragma once
// Test images from the Debian package opencv-doc. A missing file fails the test (never skips)
// with a message that names the package.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace surfvp::surf::test {

// Path of an opencv-doc example file; ADD_FAILURE and "" when it is missing.
inline std::string opencv_data(const std::string& name) {
    const std::string path = std::string(OPENCV_DATA_DIR) + "/" + name;
    if (!std::filesystem::exists(path)) {
        ADD_FAILURE() << path << " is missing: install the Debian package opencv-doc "
                      << "(apt-get install opencv-doc), which ships OpenCV's example data";
        return "";
    }
    return path;
}

// The example image as 8-bit grey; an empty Mat (and a failure) when it is missing.
inline cv::Mat opencv_gray(const std::string& name) {
    const std::string path = opencv_data(name);
    if (path.empty()) return {};
    cv::Mat img = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (img.empty()) ADD_FAILURE() << path << " exists but cannot be decoded (package opencv-doc)";
    return img;
}

}  // namespace surfvp::surf::test
