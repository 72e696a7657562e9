#include "sw/surf/image_io.h"

#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>
#include <fstream>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>  // cv::IMREAD_GRAYSCALE

#include "sw/media/media.h"

#include "sw/surf/fast_hessian.h"

namespace surfvp::surf {

QuietDecoding::QuietDecoding() : saved_stderr_(-1) {
    std::fflush(stderr);
    const int null = ::open("/dev/null", O_WRONLY);
    if (null < 0) return;
    saved_stderr_ = ::dup(STDERR_FILENO);
    if (saved_stderr_ >= 0) ::dup2(null, STDERR_FILENO);
    ::close(null);
}

QuietDecoding::~QuietDecoding() {
    if (saved_stderr_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_stderr_, STDERR_FILENO);
    ::close(saved_stderr_);
}

int minimum_image_side(const Params& params) { return filter_size(0, params.intervals - 1) + 1 + 2 * params.init_step; }

void check_image(const cv::Mat& gray8, const Params& params, const std::string& name) {
    if (gray8.empty()) throw ImageError(fmt::format("{}: image is empty (no pixels)", name));
    if (gray8.type() != CV_8UC1)
        throw ImageError(fmt::format("{}: image must be 8-bit single-channel (CV_8UC1), got {} channel(s) of depth {}",
                                     name, gray8.channels(), gray8.depth()));
    const int side = minimum_image_side(params);
    if (gray8.cols < side || gray8.rows < side)
        throw ImageError(fmt::format(
            "{}: image {}x{} is too small: one octave of the largest filter ({} pixels) needs at least {}x{}", name,
            gray8.cols, gray8.rows, filter_size(0, params.intervals - 1), side, side));
}

cv::Mat load_gray(const std::string& path, const Params& params) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw ImageError(fmt::format("{}: file does not exist", path));
    if (fs::is_directory(status)) throw ImageError(fmt::format("{}: is a directory, not an image file", path));
    if (!std::ifstream(path, std::ios::binary).good())
        throw ImageError(fmt::format("{}: file cannot be opened for reading (permissions?)", path));
    if (fs::file_size(path, ec) == 0) throw ImageError(fmt::format("{}: file is empty (0 bytes)", path));
    cv::Mat gray;
    {
        QuietDecoding quiet;
        gray = media::read_image(path, cv::IMREAD_GRAYSCALE);
    }
    if (gray.empty()) throw ImageError(fmt::format("{}: file is not an image OpenCV can decode", path));
    check_image(gray, params, path);
    return gray;
}

}  // namespace surfvp::surf
