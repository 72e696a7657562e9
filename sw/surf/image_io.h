#pragma once
// Loading the grey images the reference runs on, and the checks every entry point applies.
#include <stdexcept>
#include <string>

#include <opencv2/core/mat.hpp>

#include "sw/surf/params.h"

namespace surfvp::surf {

// A missing, unreadable, empty, undecodable or too small image. The message names the file
// (or "image" for an in-memory one) and the problem.
class ImageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// While one is alive, what the image and video libraries print on stderr (libpng's "Read
// Error", FFmpeg's complaints about a damaged stream) goes nowhere: a damaged file is then
// reported once, by the caller, with its name. Only around decoding; not thread-safe.
class QuietDecoding {
public:
    QuietDecoding();
    ~QuietDecoding();
    QuietDecoding(const QuietDecoding&) = delete;
    QuietDecoding& operator=(const QuietDecoding&) = delete;

private:
    int saved_stderr_;
};

// Smallest width and height that hold the first octave's largest filter with the border rule
// (fast_hessian.h) and room for one 3x3 non-maximum neighbourhood: L + 1 + 2 * init_step,
// 30 pixels with the default parameters.
int minimum_image_side(const Params& params);

// Throws ImageError unless `gray8` is a non-empty CV_8UC1 image of at least
// minimum_image_side(params) in both directions.
void check_image(const cv::Mat& gray8, const Params& params, const std::string& name = "image");

// Reads any image OpenCV decodes as 8-bit grey (colour is converted) and checks it with the
// given parameters.
cv::Mat load_gray(const std::string& path, const Params& params = Params{});

}  // namespace surfvp::surf
