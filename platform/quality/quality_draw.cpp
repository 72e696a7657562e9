// `surfvp draw`: a keypoint file drawn on its image as in the paper's Fig. 1, each keypoint a
// circle of radius r = 2.5 s (the region the evaluation uses) with a radius showing its
// orientation, coloured by the Laplacian sign.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "platform/quality/quality_tasks.h"
#include "platform/run/run.h"
#include "sw/eval/keypoint_file.h"
#include "sw/eval/region.h"
#include "sw/eval/text_io.h"
#include "sw/media/media.h"
#include "sw/surf/image_io.h"

namespace surfvp::quality {
namespace {

// BGR. +1 is a dark blob on a light background (sw/surf/README.md).
cv::Scalar sign_colour(int laplacian) {
    if (laplacian > 0) return {0, 0, 255};    // red
    if (laplacian < 0) return {255, 128, 0};  // blue
    return {0, 255, 255};                     // yellow: the file has no sign
}

// OpenCV draws with sub-pixel precision in fixed point with this many fractional bits; its
// integer coordinates are pixel centres, the keypoints' convention too.
constexpr int kShift = 4;
constexpr double kOne = 1 << kShift;

cv::Point fixed_point(double x, double y) {
    return {static_cast<int>(std::lround(x * kOne)), static_cast<int>(std::lround(y * kOne))};
}

void draw_keypoint(cv::Mat& canvas, const surf::Keypoint& k) {
    const double r = eval::region_radius(k);
    const cv::Scalar colour = sign_colour(k.laplacian);
    const cv::Point centre = fixed_point(k.x, k.y);
    cv::circle(canvas, centre, static_cast<int>(std::lround(r * kOne)), colour, 1, cv::LINE_AA, kShift);
    // The orientation is atan2(dy, dx) in image axes (y down), so this is its direction on
    // screen as well.
    const cv::Point tip = fixed_point(k.x + r * std::cos(k.orientation), k.y + r * std::sin(k.orientation));
    cv::line(canvas, centre, tip, colour, 1, cv::LINE_AA, kShift);
}

std::size_t outside(const surf::Keypoints& keypoints, const cv::Size& size) {
    std::size_t n = 0;
    for (const auto& k : keypoints)
        if (k.x < -0.5f || k.y < -0.5f || k.x > size.width - 0.5f || k.y > size.height - 0.5f) ++n;
    return n;
}

// Encoded in memory, then written under a temporary name and renamed, so the file is
// never seen half-written.
void write_image(const std::string& file, const cv::Mat& image) {
    const std::string extension = std::filesystem::path(file).extension().string();
    std::vector<uchar> bytes;
    if (extension.empty() || !media::encode_image(extension, image, bytes))
        throw ConfigError("--out " + file + ": OpenCV cannot write images of type '" + extension + "' (use .png)");
    read_input("--out", [&] { eval::write_file_atomically(file, std::string(bytes.begin(), bytes.end())); });
}

}  // namespace

int run_draw(const DrawCommand& c) {
    const cv::Mat gray = read_input("", [&] { return surf::load_gray(c.image); });
    const surf::Keypoints keypoints = read_input("", [&] { return eval::load_keypoints(c.keypoints); });
    // Grey underneath so that the colours are the keypoints'.
    cv::Mat canvas;
    cv::cvtColor(gray, canvas, cv::COLOR_GRAY2BGR);
    for (const auto& k : keypoints) draw_keypoint(canvas, k);
    write_image(c.out, canvas);
    if (const std::size_t n = outside(keypoints, gray.size()))
        std::fprintf(stderr, "surfvp: note: %zu of %zu keypoints lie outside the %dx%d image %s: is it their image?\n",
                     n, keypoints.size(), gray.cols, gray.rows, c.image.c_str());
    return kExitOk;
}

}  // namespace surfvp::quality
