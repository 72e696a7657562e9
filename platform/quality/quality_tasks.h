#pragma once
// The bodies of `surfvp surf`, `eval`, `eval-seq` and `draw`, apart from their CLI11
// registration (quality_commands.cpp), so each reads as plain C++ on option structs.
// Every input problem is thrown as ConfigError (exit 2) with a message naming the file or
// option; docs/quality.md is the user's description.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "platform/scenario/config.h"
#include "sw/surf/keypoint.h"
#include "sw/surf/params.h"

namespace surfvp::quality {

// How the reference SURF is run on each image: a fixed threshold, or the threshold that gives
// `target_count` keypoints on that image (surf::threshold_for_count); neither: the default.
struct SurfSettings {
    std::optional<float> threshold;
    std::optional<int> target_count;
    bool upright = false;
    int octaves = 4;
    int init_step = 1;
    std::string haar = "exact";  // or "rounded", as the chip's software (surf.haar)
    bool paper = false;          // start from surf::paper_surf() instead of surf::Params{}
    // Given only when set on the command line; otherwise from the defaults chosen above.
    std::optional<int> intervals;
    std::optional<std::string> descriptor;  // "surf" or "msurf"
    std::optional<float> max_offset;
    int threads = 0;

    surf::Params params() const;  // without the threshold, which detect() decides
};

struct Detection {
    surf::Keypoints keypoints;
    float threshold = 0;      // the one used
    size_t blobs = 0;         // with a target count: the image's blobs with a positive response
    double milliseconds = 0;  // threshold search + detect + describe
};

// Runs the reference SURF on an 8-bit grey image; `name` names it in errors (ConfigError).
Detection detect(const cv::Mat& gray, const SurfSettings& settings, const std::string& name);

struct SurfCommand {
    std::string image, out;
    SurfSettings surf;
    bool no_laplacian = false;
    bool quiet = false;
};

struct EvalCommand {
    std::string a, b;
    std::string homography;           // empty: distinguishability only
    std::vector<std::string> images;  // IMG_A IMG_B, needed with the homography
    std::optional<double> radius;
    bool laplacian = false;
};

struct EvalSeqCommand {
    std::string source;
    std::size_t frames = 0;         // 0: all
    std::vector<std::size_t> gaps;  // empty: {1}
    SurfSettings surf;
    std::string poses;               // empty: RANSAC only
    std::vector<double> intrinsics;  // fx fy u0 v0, with poses
    std::optional<double> radius;
    bool laplacian = false;
    bool table = false;          // the four rows of Table II
    bool per_pair = false;       // each pair's figures in the JSON as well
    std::string keypoints_dir;   // empty: keypoints are not written
    std::string keypoints_from;  // set: each frame's keypoints from this folder's files, no SURF
    bool quiet = false;
};

struct DrawCommand {
    std::string image, keypoints, out;
};

int run_surf(const SurfCommand& command);
int run_eval(const EvalCommand& command);
int run_eval_seq(const EvalSeqCommand& command);
int run_draw(const DrawCommand& command);

// Runs `read` and turns the input errors of sw/surf and sw/eval (ImageError, FormatError, a
// file that cannot be opened, std::invalid_argument from a parameter check) into ConfigError,
// prefixed with `context` when it is not empty. Only for reading input: a runtime_error from
// the computation itself is a bug and must stay one (exit 3).
template <class Read>
auto read_input(const std::string& context, Read&& read) -> decltype(read()) {
    try {
        return read();
    } catch (const ConfigError&) {
        throw;                               // already the user's message
    } catch (const std::runtime_error& e) {  // ImageError, FormatError, cannot open
        throw ConfigError(context.empty() ? e.what() : context + ": " + e.what());
    } catch (const std::invalid_argument& e) {
        throw ConfigError(context.empty() ? e.what() : context + ": " + e.what());
    }
}

}  // namespace surfvp::quality
