#pragma once
// The two columns of Table II and what they are measured with, for `surfvp table2` and the
// precision study: the float reference's keypoints (with some of the chip's software settings,
// or none), the chip's (a direct-mode run), and distinguishability, repeatability and
// precision of a column.
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core/types.hpp>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "platform/run/run.h"
#include "platform/scenario/config.h"
#include "sw/eval/matching.h"
#include "sw/eval/pose_geometry.h"
#include "sw/surf/keypoint.h"
#include "sw/surf/params.h"

namespace surfvp::table2 {

constexpr double kLimitedSearchPx = 200;  // paper §IV-A: "limit the correspondence search radius to 200 pixels"

// The paper's Table II, in its row order, on its own 1500-image data set (not available): a
// reference to read the results against, never a result.
struct PaperRow {
    bool limited, laplacian;
    double cpu, fpga;
    std::optional<double> gpu;
};
constexpr std::array<PaperRow, 4> kPaper{{{true, true, 0.62, 0.53, std::nullopt},
                                          {true, false, 0.61, 0.53, 0.54},
                                          {false, true, 0.43, 0.27, std::nullopt},
                                          {false, false, 0.43, 0.26, 0.27}}};

// The chip's best affordable software: the most distinguishable setting of the CPU stage that
// still lets the CPU alone hold 10 frames/s on budget_1024x768, as `surfvp quality-budget`
// measured it (docs/quality_budget.md; scenarios/budget_best_software.yaml runs it, and a test
// holds the two equal). table2 runs the chip with it beside the paper's software.
inline const std::vector<std::string> kBestAffordableSoftware{"surf.max_offset=1", "surf.upright=on",
                                                              "surf.descriptor=msurf"};

// One platform's keypoints of every frame, and how it got them.
struct Column {
    std::string name, label;
    std::vector<surf::Keypoints> frames;
    std::vector<size_t> failed;   // frames the chip did not finish: no keypoints
    std::vector<cv::Size> sizes;  // each frame's, as the chip takes it (the CPU column's)
    double threshold = 0;
    std::string threshold_rule;
    double seconds = 0;
    int exit_code = kExitOk;
    nlohmann::ordered_json simulated;  // a chip column's timed run: sim_time_s, throughput_fps, exit
};

// The float reference beside the chip: at its defaults (surf::Params, the best CPU SURF) or
// with some of the chip's software settings, so that each difference is measured alone. The
// threshold and upright setting come from the scenario.
struct Variant {
    std::string name, label;
    surf::Params params;
};

struct Geometry {
    std::vector<eval::PosedFrame> poses;  // empty: RANSAC only
    std::optional<Eigen::Matrix3d> homography;
};

// Under the chip's threshold rule (surf.target_keypoints on frame 0, held or tracked like
// libSSA2); keypoint files into `dir`/keypoints when `dir` is given.
Column cpu_column(const Config& c, const Variant& v, const std::filesystem::path& dir = {});
// The chip: a direct-mode run into `dir` (a run folder of its own), then its keypoint files;
// `sizes`: its frames' (a CPU column's), which the chip's keypoint files do not hold.
Column fpga_column(const Config& c, const std::filesystem::path& dir, const std::vector<cv::Size>& sizes);
// The CPU column, then each of the chip's software settings alone in float, then the paper's
// SURF, then all of them (the chip's software in float).
std::vector<Variant> variants(const Config& c);
Geometry read_geometry(const Config& c);  // the scenario's poses and homography (already checked)

// The measures of one cell: all pairs (i, i + gap) of a column under `matching`, F from
// RANSAC and, with poses, from the ground truth; each {mean, spread, pairs, ...}.
nlohmann::ordered_json column_row(const Column& col, size_t gap, const eval::RatioTestOptions& matching,
                                  const Geometry& g);
eval::RatioTestOptions paper_matching(const PaperRow& row);
// Every measure of one column, each computed once: per gap, the four rows in kPaper order
// (column_row), and frames 0 and 1 under the homography when the scenario has one
// (repeatability, precision of the plain ratio test, their counts).
struct Measures {
    std::vector<std::pair<size_t, std::vector<nlohmann::ordered_json>>> gaps;
    std::optional<nlohmann::ordered_json> homography;
    const std::vector<nlohmann::ordered_json>& rows(size_t gap) const;  // throws std::out_of_range
};
Measures measure(const Column& col, const std::vector<size_t>& gaps, const Geometry& g);
// One column in one line: keypoints per frame, the four rows' means on consecutive frames
// (RANSAC, and the ground truth with poses), precision and repeatability under a homography;
// from measures that include gap 1, or measured here.
nlohmann::ordered_json quality_line(const Column& col, const Measures& m);
nlohmann::ordered_json quality_line(const Column& col, const Geometry& g);

}  // namespace surfvp::table2
