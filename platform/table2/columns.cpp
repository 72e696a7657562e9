#include "platform/table2/columns.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <opencv2/core/mat.hpp>

#include "models/host/atomic_file.h"
#include "platform/workload/keypoint_sink.h"
#include "platform/workload/surf_settings.h"
#include "platform/workload/workload.h"
#include "sw/eval/distinguishability.h"
#include "sw/eval/homography.h"
#include "sw/eval/keypoint_file.h"
#include "sw/eval/repeatability.h"
#include "sw/libssa2/libssa2.h"
#include "sw/surf/surf.h"

namespace surfvp::table2 {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

namespace {

// Mean (the paper's: a pair without a ratio counts 0), spread (standard deviation over the
// pairs) and counts of one cell.
Json cell(const eval::SequenceDistinguishability& s) {
    double spread = 0;
    for (const auto& p : s.pairs) spread += (p.distinguishability - s.mean) * (p.distinguishability - s.mean);
    spread = s.pairs.empty() ? 0 : std::sqrt(spread / double(s.pairs.size()));
    return {{"mean", s.mean},
            {"spread", spread},
            {"pairs", s.pairs.size()},
            {"measured_pairs", s.measured_pairs},
            {"candidates", s.candidates},
            {"valid", s.valid}};
}

double mean_keypoints(const Column& col) {
    size_t total = 0;
    for (const auto& k : col.frames) total += k.size();
    return double(total) / double(col.frames.size());
}

}  // namespace

// Under the chip's threshold rule: the response of rank surf.target_keypoints on frame 0, held
// for every frame (or surf.threshold). Keypoint files only for the main CPU column (`dir`).
Column cpu_column(const Config& c, const Variant& v, const fs::path& dir) {
    Column col;
    col.name = v.name, col.label = v.label;
    const auto start = Clock::now();
    surf::Params p = v.params;
    const SurfWorkloadSettings s = surf_settings(c);
    p.upright = s.upright;
    const auto target = int(s.target_keypoints);
    p.threshold = float(s.threshold);
    col.threshold_rule = threshold_rule_text(c, "of this column");
    // surf.threshold_control = track: libSSA2's keypoint-count control, the same step and delay.
    const bool track = s.track;
    const size_t delay = s.tasks_in_flight;
    std::vector<double> used;
    std::vector<size_t> counts;
    if (!dir.empty()) fs::create_directories(dir / "keypoints");
    for_each_chip_frame(c, [&](size_t i, const cv::Mat& frame) {
        if (i == 0 && target > 0)
            p.threshold = surf::threshold_for_rank(surf::stored_ranked_responses(frame, p), target);
        if (track && i >= delay)
            p.threshold = float(sw::ssa2::keypoint_control_step(used[i - delay], counts[i - delay], target));
        surf::Keypoints k = surf::detect_and_describe(frame, p);
        used.push_back(p.threshold), counts.push_back(k.size()), col.sizes.push_back(frame.size());
        if (!dir.empty()) {
            const fs::path file = keypoint_file(dir, i);
            try {
                eval::write_keypoint_file(file, k);
            } catch (const std::exception& e) {
                throw EnvironmentError(fmt::format("{}: {}", file.string(), e.what()));
            }
        }
        col.frames.push_back(std::move(k));
    });
    col.threshold = used.front();  // frame 0's: the calibrated one
    col.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return col;
}

// Each of the chip's software settings alone in the float reference, then the paper's SURF at
// 4 octaves, then all of them: the first is the CPU column; the difference of the last from the
// chip is what the hardware's integer determinants and block-wise suppression cost.
std::vector<Variant> variants(const Config& c) {
    const surf::Params chip = chip_surf_params(c);
    auto with = [](auto change) {
        surf::Params p;
        change(p);
        return p;
    };
    std::vector<Variant> v{
        {"cpu", "CPU (float reference: 4 octaves of 5 intervals, offsets to 1, M-SURF, exact Haar)", surf::Params{}},
        {"cpu_2_octaves", "CPU with the chip's 2 octaves", with([](surf::Params& p) { p.octaves = 2; })},
        {"cpu_4_intervals", "CPU with the chip's 4 intervals", with([](surf::Params& p) { p.intervals = 4; })}};
    if (chip.max_offset != surf::Params{}.max_offset)
        v.push_back({"cpu_max_offset",
                     fmt::format("CPU with the chip's offset limit {} (surf.max_offset)", chip.max_offset),
                     with([&](surf::Params& p) { p.max_offset = chip.max_offset; })});
    if (chip.descriptor != surf::Params{}.descriptor)
        v.push_back({"cpu_surf_descriptor", "CPU with the chip's descriptor (Bay's SURF; surf.descriptor)",
                     with([](surf::Params& p) { p.descriptor = surf::DescriptorKind::surf; })});
    if (chip.haar != surf::Params{}.haar)
        v.push_back({"cpu_rounded_haar", "CPU with rounded Haar wavelets (surf.haar)",
                     with([&](surf::Params& p) { p.haar = chip.haar; })});
    v.push_back({"cpu_paper", "CPU as the paper's SURF (4 octaves of 4 intervals, offsets to 0.5, SURF, exact Haar)",
                 surf::paper_surf()});
    v.push_back({"cpu_chip_settings",
                 fmt::format("CPU with all the chip's software settings (2 octaves of 4 intervals, offsets to {}, {}, "
                             "surf.haar)",
                             chip.max_offset, chip.descriptor == surf::DescriptorKind::msurf ? "M-SURF" : "SURF"),
                 chip});
    return v;
}

// The chip: a direct-mode run into `dir` (a run folder of its own), then its keypoint files.
Column fpga_column(const Config& c, const fs::path& dir, const std::vector<cv::Size>& sizes) {
    Column col;
    col.name = "fpga", col.label = "FPGA (the modelled chip)";
    col.sizes = sizes;
    const auto start = Clock::now();
    fs::create_directories(dir);
    col.exit_code = run_direct(c, dir);
    const Json report = Json::parse(std::ifstream(dir / "report.json"));
    col.threshold = report.value("threshold", 0.0);
    col.threshold_rule = report.value("threshold_rule", "");
    for (size_t i = 0; i < surf_settings(c).frames; ++i) {
        const fs::path file = keypoint_file(dir, i);
        if (!fs::exists(file)) {  // a failed frame writes none
            col.failed.push_back(i);
            col.frames.emplace_back();
            continue;
        }
        col.frames.push_back(eval::load_keypoints(file));
    }
    col.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return col;
}

eval::RatioTestOptions paper_matching(const PaperRow& row) {
    eval::RatioTestOptions matching;
    if (row.limited) matching.search_radius = kLimitedSearchPx;
    matching.same_laplacian = row.laplacian;
    return matching;
}

Json column_row(const Column& col, size_t gap, const eval::RatioTestOptions& matching, const Geometry& g) {
    eval::DistinguishabilityOptions options;
    options.matching = matching;
    Json j = {{"ransac", cell(eval::sequence_distinguishability(col.frames, gap, options))}};
    if (!g.poses.empty())
        j["ground_truth"] = cell(eval::sequence_distinguishability(
            col.frames, gap,
            [&](size_t a, size_t b) {
                return eval::fundamental_from_poses(eval::kCastleIntrinsics, g.poses[a].c_m_o, g.poses[b].c_m_o);
            },
            options));
    return j;
}

const std::vector<Json>& Measures::rows(size_t gap) const {
    for (const auto& [k, rows] : gaps)
        if (k == gap) return rows;
    throw std::out_of_range(fmt::format("table2: gap {} was not measured", gap));
}

Measures measure(const Column& col, const std::vector<size_t>& gaps, const Geometry& g) {
    Measures m;
    for (size_t gap : gaps) {
        std::vector<Json> rows;
        for (const PaperRow& paper : kPaper) rows.push_back(column_row(col, gap, paper_matching(paper), g));
        m.gaps.emplace_back(gap, std::move(rows));
    }
    if (g.homography) {
        const auto& f = col.frames;
        const auto rep = eval::repeatability(f[0], f[1], *g.homography, col.sizes[0], col.sizes[1]);
        const auto prec = eval::matching_precision(f[0], f[1], *g.homography);
        m.homography = Json{{"keypoints", {f[0].size(), f[1].size()}},
                            {"repeatability", rep.repeatability},
                            {"correspondences", rep.correspondences},
                            {"matches", rep.matches.size()},
                            {"precision", prec.precision},
                            {"precision_candidates", prec.candidates},
                            {"precision_correct", prec.correct}};
    }
    return m;
}

Json quality_line(const Column& col, const Measures& m) {
    Json means = Json::array(), spreads = Json::array(), truth = Json::array(), measured = Json::array();
    size_t pairs = 0;
    for (const Json& row : m.rows(1)) {
        means.push_back(row["ransac"]["mean"]);
        measured.push_back(row["ransac"]["measured_pairs"].get<size_t>() > 0);
        spreads.push_back(row["ransac"]["spread"]);
        pairs = row["ransac"]["pairs"].get<size_t>();
        if (row.contains("ground_truth")) truth.push_back(row["ground_truth"]["mean"]);
    }
    Json j = {{"name", col.name}, {"label", col.label},       {"keypoints_per_frame", mean_keypoints(col)},
              {"ransac", means},  {"ransac_spread", spreads}, {"pairs", pairs}};
    j["ransac_measured"] = measured;  // false: no pair of the cell gave a ratio (its mean 0 is no measurement)
    if (!truth.empty()) j["ground_truth"] = truth;
    if (m.homography) {
        j["precision"] = (*m.homography)["precision"];
        j["repeatability"] = (*m.homography)["repeatability"];
    }
    return j;
}

Json quality_line(const Column& col, const Geometry& g) { return quality_line(col, measure(col, {1}, g)); }

Geometry read_geometry(const Config& c) {
    Geometry g;  // check_scenario has read and checked both files
    const EvalSettings e = eval_settings(c);
    if (!e.poses.empty()) g.poses = eval::list_posed_frames(e.poses);
    if (!e.homography.empty()) g.homography = eval::read_homography_file(e.homography);
    return g;
}

}  // namespace surfvp::table2
