#pragma once
// The benchmarks' frame: graf1 (opencv-doc) resized to the chip's 1024x768, as the budget
// scenario's. Exits with a message naming the package when the image is missing.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace surfvp::bench {

constexpr int kFrameWidth = 1024, kFrameHeight = 768;

inline const cv::Mat& frame() {
    static const cv::Mat img = [] {
        const std::string path = OPENCV_DATA_DIR "/graf1.png";
        cv::Mat gray = cv::imread(path, cv::IMREAD_GRAYSCALE);
        if (gray.empty()) {
            std::fprintf(stderr, "%s is missing: install the Debian package opencv-doc\n", path.c_str());
            std::exit(1);
        }
        cv::Mat resized;
        cv::resize(gray, resized, cv::Size(kFrameWidth, kFrameHeight), 0, 0, cv::INTER_AREA);
        return resized;
    }();
    return img;
}

}  // namespace surfvp::bench
