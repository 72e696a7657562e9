#include "platform/workload/surf_evaluation.h"

#include <filesystem>
#include <fmt/format.h>

#include "platform/scenario/config.h"
#include "platform/workload/surf_settings.h"
#include "sw/eval/distinguishability.h"
#include "sw/eval/homography.h"
#include "sw/eval/pose_geometry.h"
#include "sw/eval/repeatability.h"

namespace surfvp {
namespace fs = std::filesystem;
namespace {

// Pairs (i, i + gap) the evaluation measures: consecutive frames and eval.gap.
std::vector<size_t> evaluated_gaps(const Config& c) {
    std::vector<size_t> gaps{1};
    if (const uint64_t gap = eval_settings(c).gap; gap > 1) gaps.push_back(gap);
    return gaps;
}

}  // namespace

// The evaluation's geometry, read before anything is built: a homography from frame 0 to
// frame 1 at the frames' own size, and camera poses that belong to the very frames the source
// gives, one each.
void check_eval_inputs(const Config& c, const SourceFrames& frames) {
    const EvalSettings settings = eval_settings(c);
    const std::string& homography = settings.homography;
    if (!homography.empty()) {
        try {
            eval::read_homography_file(homography);
        } catch (const std::exception& e) {
            throw ConfigError(fmt::format("{}: {}", c.where("eval.homography"), e.what()));
        }
        if (frames.first.size() != frames.original)
            throw ConfigError(
                fmt::format("{}: the homography maps frame 0 to frame 1 at their own size ({}x{}), but "
                            "surf.width x surf.height (from {}) resize them to {}x{}; set both to 0",
                            c.where("eval.homography"), frames.original.width, frames.original.height,
                            c.source_of("surf.width"), frames.first.cols, frames.first.rows));
    }
    const std::string& poses = settings.poses;
    if (poses.empty()) return;
    std::vector<eval::PosedFrame> posed;
    try {
        posed = eval::list_posed_frames(poses);
    } catch (const std::exception& e) {
        throw ConfigError(fmt::format("{}: {}", c.where("eval.poses"), e.what()));
    }
    if (frames.files.size() != frames.count)
        throw ConfigError(
            fmt::format("{}: poses belong to image files, but surf.source {} (from {}) is one image or a video",
                        c.where("eval.poses"), surf_settings(c).source, c.source_of("surf.source")));
    if (posed.size() < frames.count)
        throw ConfigError(fmt::format("{}: {} poses for {} frames (surf.frames from {})", c.where("eval.poses"),
                                      posed.size(), frames.count, c.source_of("surf.frames")));
    // The evaluation's pairs (evaluate() below) need two distinct camera centres.
    for (size_t i = 0; i < frames.count; ++i)
        for (size_t gap : evaluated_gaps(c)) {
            const size_t j = i + gap;
            if (j < frames.count) try {
                    eval::fundamental_from_poses(eval::kCastleIntrinsics, posed[i].c_m_o, posed[j].c_m_o);
                } catch (const std::invalid_argument& e) {
                    throw ConfigError(fmt::format("{}: frames {} and {} ({} and {}): {}", c.where("eval.poses"), i, j,
                                                  posed[i].pose_file.string(), posed[j].pose_file.string(), e.what()));
                }
        }
    for (size_t i = 0; i < frames.files.size(); ++i) {
        std::error_code ec;
        if (!fs::equivalent(frames.files[i], posed[i].image, ec))
            throw ConfigError(fmt::format("{}: frame {} is {}, but pose {} ({}) belongs to {}", c.where("eval.poses"),
                                          i, frames.files[i].string(), i, posed[i].pose_file.filename().string(),
                                          posed[i].image.string()));
    }
}

bool evaluation_needs(const Config& config, size_t frame) {
    const EvalSettings s = eval_settings(config);
    return (frame <= 1 && !s.homography.empty()) || !s.poses.empty();
}

nlohmann::ordered_json evaluate(const Config& config, const SourceFrames& source,
                                const std::vector<const surf::Keypoints*>& keypoints) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    const EvalSettings settings = eval_settings(config);
    const std::string& homography = settings.homography;
    if (!homography.empty() && keypoints.size() >= 2) {
        const Eigen::Matrix3d h = eval::read_homography_file(homography);
        const cv::Size size = source.sizes[0], size_b = source.sizes[1];
        const auto rep = eval::repeatability(*keypoints[0], *keypoints[1], h, size, size_b);
        const auto prec = eval::matching_precision(*keypoints[0], *keypoints[1], h);
        out["homography"] = {{"repeatability", rep.repeatability},
                             {"correspondences", rep.correspondences},
                             {"precision", prec.precision},
                             {"candidates", prec.candidates}};
    }
    const std::string& poses = settings.poses;
    if (!poses.empty() && keypoints.size() >= 2) {
        std::vector<surf::Keypoints> all;
        for (const surf::Keypoints* k : keypoints) all.push_back(*k);
        const auto posed = eval::list_posed_frames(poses);
        const eval::CameraIntrinsics k = eval::kCastleIntrinsics;
        for (size_t gap : evaluated_gaps(config)) {
            if (gap >= keypoints.size()) continue;
            const auto ransac = eval::sequence_distinguishability(all, gap);
            const auto truth = eval::sequence_distinguishability(all, gap, [&](size_t i, size_t j) {
                return eval::fundamental_from_poses(k, posed.at(i).c_m_o, posed.at(j).c_m_o);
            });
            out[fmt::format("distinguishability_gap{}", gap)] = {
                {"ransac", ransac.mean}, {"ground_truth", truth.mean}, {"pairs", ransac.pairs.size()}};
        }
    }
    return out;
}

}  // namespace surfvp
