#include "platform/table2/table2.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "models/common/atomic_file.h"
#include "platform/run/output_folder.h"
#include "platform/run/run.h"
#include "platform/scenario/scenario.h"
#include "platform/workload/workload.h"
#include "sw/eval/distinguishability.h"
#include "sw/eval/homography.h"
#include "sw/eval/keypoint_file.h"
#include "sw/eval/pose_geometry.h"
#include "sw/eval/repeatability.h"
#include "sw/libssa2/libssa2.h"
#include "sw/surf/surf.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

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

// One platform's keypoints of every frame, and how it got them.
struct Column {
    std::string name, label;
    std::vector<surf::Keypoints> frames;
    std::vector<size_t> failed;  // frames the chip did not finish: no keypoints
    std::vector<cv::Size> sizes;  // each frame's, as the chip takes it (the CPU column's)
    double threshold = 0;
    std::string threshold_rule;
    double seconds = 0;
    int exit_code = kExitOk;
};

fs::path keypoint_file(const fs::path& dir, size_t frame) { return dir / "keypoints" / fmt::format("frame_{:04}.surf", frame); }

// The float reference beside the chip: at its defaults (4 octaves, exact Haar wavelets) or
// with some of the chip's software settings, so that each difference is measured alone.
struct Variant {
    std::string name, label;
    int octaves = 4;
    surf::HaarMode haar = surf::HaarMode::exact;
};

// Under the chip's threshold rule: the response of rank surf.target_keypoints on frame 0, held
// for every frame (or surf.threshold). Keypoint files only for the main CPU column (`dir`).
Column cpu_column(const Config& c, const Variant& v, const fs::path& dir = {}) {
    Column col;
    col.name = v.name, col.label = v.label;
    const auto start = Clock::now();
    surf::Params p;
    p.octaves = v.octaves;
    p.haar = v.haar;
    p.upright = c.choice("surf.upright") == "on";
    const auto target = int(c.count("surf.target_keypoints"));
    p.threshold = float(c.real("surf.threshold"));
    col.threshold_rule = "surf.threshold";
    // surf.threshold_control = track: libSSA2's keypoint-count control, the same step and delay.
    const bool track = c.choice("surf.threshold_control") == "track";
    const size_t delay = c.count("surf.tasks_in_flight");
    std::vector<double> used;
    std::vector<size_t> counts;
    if (!dir.empty()) fs::create_directories(dir / "keypoints");
    for_each_chip_frame(c, [&](size_t i, const cv::Mat& frame) {
        if (i == 0 && target > 0) {
            p.threshold = surf::threshold_for_rank(surf::ranked_responses(frame, p), target);
            col.threshold_rule = track ? fmt::format("the {}th strongest response on frame 0 (surf.target_keypoints), then "
                                                     "each frame's from the keypoint count of the frame {} before it (track)",
                                                     target, delay)
                                       : fmt::format("the {}th strongest response on frame 0 (surf.target_keypoints), held "
                                                     "for every frame", target);
        }
        if (track && i >= delay) p.threshold = float(sw::ssa2::keypoint_control_step(used[i - delay], counts[i - delay], target));
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

// Each of the chip's software settings alone in the float reference, then both: the first is
// the CPU column; the difference of the last from the chip is what the hardware's integer
// determinants and block-wise suppression cost.
std::vector<Variant> variants(const Config& c) {
    const auto haar = c.choice("surf.haar") == "rounded" ? surf::HaarMode::rounded : surf::HaarMode::exact;
    std::vector<Variant> v{{"cpu", "CPU (float reference, 4 octaves)", 4, surf::HaarMode::exact},
                           {"cpu_2_octaves", "CPU with the chip's 2 octaves", 2, surf::HaarMode::exact}};
    if (haar == surf::HaarMode::rounded) {
        v.push_back({"cpu_rounded_haar", "CPU with rounded Haar wavelets (surf.haar)", 4, haar});
        v.push_back({"cpu_chip_settings", "CPU with the chip's software settings (2 octaves, rounded Haar)", 2, haar});
    }
    return v;
}

// The chip: a direct-mode run into `dir` (a run folder of its own), then its keypoint files.
Column fpga_column(const Config& c, const fs::path& dir) {
    Column col;
    col.name = "fpga", col.label = "FPGA (the modelled chip)";
    const auto start = Clock::now();
    fs::create_directories(dir);
    col.exit_code = run_direct(c, dir);
    const Json report = Json::parse(std::ifstream(dir / "report.json"));
    col.threshold = report.value("threshold", 0.0);
    col.threshold_rule = report.value("threshold_rule", "");
    for (size_t i = 0; i < c.count("surf.frames"); ++i) {
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

// Mean (the paper's: a pair without a ratio counts 0), spread (standard deviation over the
// pairs) and counts of one cell.
Json cell(const eval::SequenceDistinguishability& s) {
    double spread = 0;
    for (const auto& p : s.pairs) spread += (p.distinguishability - s.mean) * (p.distinguishability - s.mean);
    spread = s.pairs.empty() ? 0 : std::sqrt(spread / double(s.pairs.size()));
    return {{"mean", s.mean}, {"spread", spread}, {"pairs", s.pairs.size()}, {"measured_pairs", s.measured_pairs},
            {"candidates", s.candidates}, {"valid", s.valid}};
}

struct Geometry {
    std::vector<eval::PosedFrame> poses;  // empty: RANSAC only
    std::optional<Eigen::Matrix3d> homography;
};

Json column_row(const Column& col, size_t gap, const eval::RatioTestOptions& matching, const Geometry& g) {
    eval::DistinguishabilityOptions options;
    options.matching = matching;
    Json j = {{"ransac", cell(eval::sequence_distinguishability(col.frames, gap, options))}};
    if (!g.poses.empty())
        j["ground_truth"] = cell(eval::sequence_distinguishability(
            col.frames, gap,
            [&](size_t a, size_t b) { return eval::fundamental_from_poses(eval::kCastleIntrinsics, g.poses[a].c_m_o, g.poses[b].c_m_o); },
            options));
    return j;
}

Json gap_table(const std::vector<Column>& columns, size_t gap, const Geometry& g) {
    Json rows = Json::array();
    for (const PaperRow& paper : kPaper) {
        eval::RatioTestOptions matching;
        if (paper.limited) matching.search_radius = kLimitedSearchPx;
        matching.same_laplacian = paper.laplacian;
        Json row = {{"limited_search", paper.limited}, {"laplacian", paper.laplacian},
                    {"search_radius_px", paper.limited ? Json(kLimitedSearchPx) : Json(nullptr)}};
        for (const Column& col : columns) row[col.name] = column_row(col, gap, matching, g);
        if (gap == 1)
            row["paper"] = {{"cpu", paper.cpu}, {"fpga", paper.fpga}, {"gpu", paper.gpu ? Json(*paper.gpu) : Json(nullptr)}};
        rows.push_back(std::move(row));
    }
    return {{"gap", gap}, {"rows", std::move(rows)}};
}

// Frames 0 and 1 under the scenario's homography: repeatability, and precision of the plain
// ratio test.
Json homography_figures(const Column& col, const Eigen::Matrix3d& h, const std::vector<cv::Size>& sizes) {
    const auto rep = eval::repeatability(col.frames[0], col.frames[1], h, sizes[0], sizes[1]);
    const auto prec = eval::matching_precision(col.frames[0], col.frames[1], h);
    return {{"keypoints", {col.frames[0].size(), col.frames[1].size()}},
            {"repeatability", rep.repeatability},
            {"correspondences", rep.correspondences},
            {"matches", rep.matches.size()},
            {"precision", prec.precision},
            {"precision_candidates", prec.candidates},
            {"precision_correct", prec.correct}};
}

double mean_keypoints(const Column& col) {
    size_t total = 0;
    for (const auto& k : col.frames) total += k.size();
    return double(total) / double(col.frames.size());
}

// One line of the contributions table: the four rows' means on consecutive frames (RANSAC,
// and the ground truth with poses), precision under a homography.
Json contribution(const Column& col, const Geometry& g) {
    Json means = Json::array(), truth = Json::array();
    for (const PaperRow& paper : kPaper) {
        eval::RatioTestOptions matching;
        if (paper.limited) matching.search_radius = kLimitedSearchPx;
        matching.same_laplacian = paper.laplacian;
        const Json row = column_row(col, 1, matching, g);
        means.push_back(row["ransac"]["mean"]);
        if (row.contains("ground_truth")) truth.push_back(row["ground_truth"]["mean"]);
    }
    Json j = {{"name", col.name}, {"label", col.label}, {"keypoints_per_frame", mean_keypoints(col)}, {"ransac", means}};
    if (!truth.empty()) j["ground_truth"] = truth;
    if (g.homography) {
        const auto prec = eval::matching_precision(col.frames[0], col.frames[1], *g.homography);
        j["precision"] = prec.precision;
    }
    return j;
}

Json column_summary(const Column& col) {
    size_t total = 0, least = SIZE_MAX, most = 0;
    for (const auto& k : col.frames) total += k.size(), least = std::min(least, k.size()), most = std::max(most, k.size());
    return {{"label", col.label},
            {"threshold", col.threshold},
            {"threshold_rule", col.threshold_rule},
            {"keypoints_per_frame", {{"mean", double(total) / double(col.frames.size())}, {"min", least}, {"max", most}}},
            {"failed_frames", col.failed},
            {"seconds", col.seconds}};
}

// Every way the two columns differ, by design. Each can be switched off alone (surfvp surf's
// options, the chip's parameters); docs/table2.md says how.
Json differences(const Config& c) {
    return Json::array(
        {{{"what", "octaves"}, {"cpu", "4"}, {"fpga", "2 (the FHG's 2 octaves x 4 intervals)"}},
         {{"what", "Haar wavelets of orientation and descriptor"},
          {"cpu", "exact (sub-pixel sample positions)"},
          {"fpga", fmt::format("{} (surf.haar)", c.choice("surf.haar"))}},
         {{"what", "determinants"},
          {"cpu", "float"},
          {"fpga", "integer, at the FHG's fixed-point widths (fhg.* precision parameters)"}},
         {{"what", "non-maximum suppression"},
          {"cpu", "3x3x3 in float"},
          {"fpga", "partial, in each 2x2 determinant block (LocalMaxFinder), re-checked in software over the integer determinants"}},
         {{"what", "threshold"},
          {"cpu", "calibrated on frame 0 with 4 octaves"},
          {"fpga", "calibrated on frame 0 with 2 octaves (the float reference limited to the chip's octaves), in the FHG's units"}}});
}

std::string figure(const Json& cell) {
    return fmt::format("{:.3f} ± {:.3f} ({})", cell["mean"].get<double>(), cell["spread"].get<double>(),
                       cell["pairs"].get<size_t>());
}

std::string row_label(const Json& row) {
    return fmt::format("{} | {}", row["limited_search"].get<bool>() ? "Y" : "N", row["laplacian"].get<bool>() ? "Y" : "N");
}

void markdown_gap(std::string& md, const Json& gap, const char* measure, const char* title) {
    const size_t k = gap["gap"].get<size_t>();
    md += fmt::format("\n## Distinguishability, frames (i, i + {}), {}\n\n", k, title);
    const bool paper = gap["rows"][0].contains("paper");
    md += "| limited search | Laplacian | CPU | FPGA | FPGA − CPU |";
    md += paper ? " paper CPU | paper FPGA |\n|---|---|---|---|---|---|---|\n" : "\n|---|---|---|---|---|\n";
    for (const Json& row : gap["rows"]) {
        const Json &cpu = row["cpu"][measure], &fpga = row["fpga"][measure];
        const double change = std::round((fpga["mean"].get<double>() - cpu["mean"].get<double>()) * 1000) / 1000;
        md += fmt::format("| {} | {} | {} | {:+.3f} |", row_label(row), figure(cpu), figure(fpga), change + 0.0);  // no -0.000
        if (paper) md += fmt::format(" {:.2f} | {:.2f} |", row["paper"]["cpu"].get<double>(), row["paper"]["fpga"].get<double>());
        md += "\n";
    }
}

void markdown_contributions(std::string& md, const Json& lines) {
    const bool truth = lines[0].contains("ground_truth"), precision = lines[0].contains("precision");
    md += "\n## What each difference costs\n\nThe float reference with the chip's software settings, one at a time and then "
          "together (the same threshold rule, each calibrated on its own frame 0); what remains between the last and the "
          "chip is the hardware's: integer determinants and block-wise suppression. Frames (i, i + 1), distinguishability "
          "with RANSAC F";
    md += truth ? " (ground truth in brackets)" : "";
    md += precision ? "; precision of frames 0 and 1 under the homography" : "";
    md += ".\n\n| | keypoints per frame | Y Y | Y N | N Y | N N |";
    md += precision ? " precision |\n|---|---|---|---|---|---|---|\n" : "\n|---|---|---|---|---|---|\n";
    for (const Json& line : lines) {
        md += fmt::format("| {} | {:.1f} |", line["label"].get<std::string>(), line["keypoints_per_frame"].get<double>());
        for (size_t i = 0; i < 4; ++i) {
            md += fmt::format(" {:.3f}", line["ransac"][i].get<double>());
            if (truth) md += fmt::format(" ({:.3f})", line["ground_truth"][i].get<double>());
            md += " |";
        }
        if (precision) md += fmt::format(" {:.3f} |", line["precision"].get<double>());
        md += "\n";
    }
}

std::string markdown(const Json& r) {
    std::string md = fmt::format("# Table II: {}\n\n{}\n\n", r["scenario"]["name"].get<std::string>(),
                                 r["scenario"]["description"].get<std::string>());
    md += fmt::format("{} frames of {}x{} from `{}`. Each cell: mean ± standard deviation over the pairs (pairs); a pair "
                      "without a measured ratio counts 0, as in the paper. Limited search: {:g} px.\n\n",
                      r["frames"].get<size_t>(), r["image"]["width"].get<int>(), r["image"]["height"].get<int>(),
                      r["source"].get<std::string>(), kLimitedSearchPx);
    md += "| column | keypoints per frame | threshold | rule | failed frames | time |\n|---|---|---|---|---|---|\n";
    for (const char* name : {"cpu", "fpga"}) {
        const Json& c = r["columns"][name];
        md += fmt::format("| {} | {:.1f} ({}..{}) | {:.6g} | {} | {} | {:.1f} s |\n", c["label"].get<std::string>(),
                          c["keypoints_per_frame"]["mean"].get<double>(), c["keypoints_per_frame"]["min"].get<size_t>(),
                          c["keypoints_per_frame"]["max"].get<size_t>(), c["threshold"].get<double>(),
                          c["threshold_rule"].get<std::string>(), c["failed_frames"].size(), c["seconds"].get<double>());
    }
    md += "\nThe FPGA column is a run of the chip in direct mode (the same driver, cores and software without "
          "SystemC): its keypoints are the VP's byte for byte. Its run folder is `fpga/`; the CPU's keypoint files are in "
          "`cpu/keypoints/`.\n";
    for (const Json& gap : r["gaps"]) {
        markdown_gap(md, gap, "ransac", "F from RANSAC (the paper's measure)");
        if (gap["rows"][0]["cpu"].contains("ground_truth")) markdown_gap(md, gap, "ground_truth", "F from the camera poses");
    }
    if (r.contains("homography")) {
        md += "\n## Frames 0 and 1 under the homography\n\nOn a planar scene every F = [e']x H fits the true "
              "correspondences, so RANSAC's F accepts more than the homography does: precision is the figure to compare "
              "here, not the distinguishability above.\n\n| column | keypoints | repeatability | precision (correct / "
              "candidates) |\n|---|---|---|---|\n";
        for (const char* name : {"cpu", "fpga"}) {
            const Json& h = r["homography"][name];
            md += fmt::format("| {} | {} / {} | {:.3f} | {:.3f} ({} / {}) |\n", name, h["keypoints"][0].get<size_t>(),
                              h["keypoints"][1].get<size_t>(), h["repeatability"].get<double>(), h["precision"].get<double>(),
                              h["precision_correct"].get<size_t>(), h["precision_candidates"].get<size_t>());
        }
    }
    if (r.contains("contributions")) markdown_contributions(md, r["contributions"]);
    md += "\nThe paper's columns are its own figures on its own 1500-image data set (not available): a reference to "
          "read these against, not a result of this run.\n\n## What the columns differ in\n\n| | CPU | FPGA |\n|---|---|---|\n";
    for (const Json& d : r["differences"])
        md += fmt::format("| {} | {} | {} |\n", d["what"].get<std::string>(), d["cpu"].get<std::string>(),
                          d["fpga"].get<std::string>());
    return md;
}

void print_summary(const Json& r, const fs::path& dir) {
    const Json& gap = r["gaps"][0];
    for (const Json& row : gap["rows"])
        std::fprintf(stderr, "surfvp: table2: limited %s  Laplacian %s  CPU %.3f  FPGA %.3f\n",
                     row["limited_search"].get<bool>() ? "Y" : "N", row["laplacian"].get<bool>() ? "Y" : "N",
                     row["cpu"]["ransac"]["mean"].get<double>(), row["fpga"]["ransac"]["mean"].get<double>());
    std::fprintf(stderr, "surfvp: table2: %s: report in %s\n", r["scenario"]["name"].get<std::string>().c_str(),
                 (dir / "report.md").string().c_str());
}

Geometry read_geometry(const Config& c) {
    Geometry g;  // check_scenario has read and checked both files
    if (!c.text("eval.poses").empty()) g.poses = eval::list_posed_frames(c.text("eval.poses"));
    if (!c.text("eval.homography").empty()) g.homography = eval::read_homography_file(c.text("eval.homography"));
    return g;
}

}  // namespace

int table2_command(const Table2Options& o) {
    const Config config = load_scenario(resolve_scenario(o.scenario), o.sets);
    if (config.choice("run.workload") != "surf")
        throw ConfigError(fmt::format("{}: table2 needs a SURF scenario (run.workload: surf)", config.where("run.workload")));
    if (config.count("surf.frames") < 2)
        throw ConfigError(fmt::format("{}: table2 compares frame pairs: surf.frames must be at least 2", config.where("surf.frames")));
    if (!config.faults.empty())
        throw ConfigError(fmt::format("{}: faults: table2 runs the chip without time; run the scenario without faults",
                                      config.faults.front().origin));
    check_scenario(config);
    const Geometry geometry = read_geometry(config);
    OutputFolder out(o.out.empty() ? fs::path("traces") / config.name : fs::path(o.out));
    const fs::path staging = out.staging();
    Json r;
    try {
        const std::vector<Variant> float_variants = variants(config);
        const std::vector<Column> columns{cpu_column(config, float_variants[0], staging / "cpu"),
                                          fpga_column(config, staging / "fpga")};
        const Json fpga_report = Json::parse(std::ifstream(staging / "fpga" / "report.json"));
        r["surfvp_version"] = SURFVP_VERSION;
        r["scenario"] = {{"name", config.name}, {"file", config.file}, {"description", config.description}};
        r["source"] = config.text("surf.source");
        r["frames"] = config.count("surf.frames");
        r["image"] = fpga_report["image"];
        r["chip_run_passed"] = fpga_report["passed"];
        r["columns"] = Json::object();
        for (const Column& col : columns) r["columns"][col.name] = column_summary(col);
        r["gaps"] = Json::array();
        std::vector<size_t> gaps{1};
        if (config.count("eval.gap") > 1) gaps.push_back(config.count("eval.gap"));
        for (size_t gap : gaps)
            if (gap < config.count("surf.frames")) r["gaps"].push_back(gap_table(columns, gap, geometry));
        if (geometry.homography) {
            for (const Column& col : columns)
                r["homography"][col.name] = homography_figures(col, *geometry.homography, columns[0].sizes);
        }
        r["differences"] = differences(config);
        r["contributions"] = Json::array({contribution(columns[0], geometry)});
        for (size_t i = 1; i < float_variants.size(); ++i)
            r["contributions"].push_back(contribution(cpu_column(config, float_variants[i]), geometry));
        r["contributions"].push_back(contribution(columns[1], geometry));
        write_file_atomically(staging / "report.json", r.dump(2) + "\n");
        write_file_atomically(staging / "report.md", markdown(r));
        write_file_atomically(staging / "config.yaml", config.to_yaml());
        out.publish();
        if (!o.quiet) print_summary(r, out.folder());
        return columns[1].exit_code;
    } catch (const EnvironmentError& e) {
        throw EnvironmentError(fmt::format("{}; what was in {} before is as it was", out.as_published(e.what()),
                                           out.folder().string()));
    }
}

}  // namespace surfvp
