// `surfvp eval`: the paper's distinguishability of two keypoint files and, under a known
// homography, the detector's repeatability and the matching precision.
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "platform/quality/quality_json.h"
#include "platform/quality/quality_tasks.h"
#include "platform/run/run.h"
#include "sw/eval/homography.h"
#include "sw/eval/keypoint_file.h"
#include "sw/eval/repeatability.h"
#include "sw/surf/image_io.h"

namespace surfvp::quality {
namespace {

using nlohmann::ordered_json;

// Matching compares descriptors, so detector-only files (dimension 0 or 1) cannot be used.
surf::Keypoints read_described_keypoints(const std::string& file) {
    const eval::KeypointFile read = read_input("", [&] { return eval::read_keypoint_file(file); });
    if (read.dimension < 64)
        throw ConfigError(file + ": the keypoints have no descriptors (dimension " + std::to_string(read.dimension) +
                          "); eval matches descriptors, so it needs SURF-64 files (dimension 64 or 65)");
    return read.keypoints;
}

cv::Size image_size(const std::string& file) {
    const cv::Mat image = read_input("--images", [&] { return surf::load_gray(file); });
    return image.size();
}

// --laplacian on files without signs would silently match 0 with 0 only: say so.
void warn_unsigned(const std::string& file, const surf::Keypoints& keypoints) {
    for (const auto& k : keypoints) {
        if (k.laplacian == 0) {
            std::fprintf(stderr,
                         "surfvp: note: %s has keypoints without a Laplacian sign; --laplacian matches "
                         "them only with each other\n",
                         file.c_str());
            return;
        }
    }
}

void add_homography_measures(ordered_json& out, const EvalCommand& c, const surf::Keypoints& a,
                             const surf::Keypoints& b, const eval::RatioTestOptions& matching) {
    const Eigen::Matrix3d h = read_input("--homography", [&] { return eval::read_homography_file(c.homography); });
    const cv::Size size_a = image_size(c.images.at(0)), size_b = image_size(c.images.at(1));
    const eval::RepeatabilityResult rep = eval::repeatability(a, b, h, size_a, size_b);
    const eval::PrecisionResult precision = eval::matching_precision(a, b, h, matching);
    out["repeatability"] = rep.repeatability;
    out["correspondences"] = rep.correspondences;
    out["precision"] = precision.precision;
    out["matches"] = rep.matches.size();
    out["visible_a"] = rep.visible_a;
    out["visible_b"] = rep.visible_b;
    out["precision_candidates"] = precision.candidates;
    out["precision_correct"] = precision.correct;
    out["homography"] = c.homography;
    out["image_a"] = {{"file", c.images[0]}, {"width", size_a.width}, {"height", size_a.height}};
    out["image_b"] = {{"file", c.images[1]}, {"width", size_b.width}, {"height", size_b.height}};
}

}  // namespace

int run_eval(const EvalCommand& c) {
    const surf::Keypoints a = read_described_keypoints(c.a), b = read_described_keypoints(c.b);
    eval::DistinguishabilityOptions options;
    options.matching.search_radius = c.radius;
    options.matching.same_laplacian = c.laplacian;
    if (c.laplacian) {
        warn_unsigned(c.a, a);
        warn_unsigned(c.b, b);
    }
    const eval::DistinguishabilityResult d = eval::distinguishability(a, b, options);

    ordered_json out;
    out["candidates"] = d.candidates;
    out["valid"] = d.valid;
    out["distinguishability"] = d.distinguishability;
    out["status"] = status_name(d.status);
    if (!c.homography.empty()) add_homography_measures(out, c, a, b, options.matching);
    out["a"] = {{"file", c.a}, {"keypoints", a.size()}};
    out["b"] = {{"file", c.b}, {"keypoints", b.size()}};
    out["matching"] = matching_json(options.matching);
    std::cout << out.dump(2) << std::endl;
    return kExitOk;
}

}  // namespace surfvp::quality
