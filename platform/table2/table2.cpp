#include "platform/table2/table2.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <optional>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>

#include "models/host/atomic_file.h"
#include "platform/run/output_folder.h"
#include "platform/run/progress_line.h"
#include "platform/run/resimulation.h"
#include "platform/run/run.h"
#include "platform/scenario/run_settings.h"
#include "platform/scenario/scenario.h"
#include "platform/table2/columns.h"
#include "platform/workload/surf_settings.h"

namespace surfvp {
namespace {
using namespace table2;
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

Json gap_table(const std::vector<Column>& columns, const std::vector<Measures>& measures, size_t gap) {
    Json rows = Json::array();
    for (size_t r = 0; r < kPaper.size(); ++r) {
        const PaperRow& paper = kPaper[r];
        Json row = {{"limited_search", paper.limited},
                    {"laplacian", paper.laplacian},
                    {"search_radius_px", paper.limited ? Json(kLimitedSearchPx) : Json(nullptr)}};
        for (size_t c = 0; c < columns.size(); ++c) row[columns[c].name] = measures[c].rows(gap)[r];
        if (gap == 1)
            row["paper"] = {
                {"cpu", paper.cpu}, {"fpga", paper.fpga}, {"gpu", paper.gpu ? Json(*paper.gpu) : Json(nullptr)}};
        rows.push_back(std::move(row));
    }
    return {{"gap", gap}, {"rows", std::move(rows)}};
}

Json column_summary(const Column& col) {
    size_t total = 0, least = SIZE_MAX, most = 0;
    for (const auto& k : col.frames)
        total += k.size(), least = std::min(least, k.size()), most = std::max(most, k.size());
    Json j = {
        {"label", col.label},
        {"threshold", col.threshold},
        {"threshold_rule", col.threshold_rule},
        {"keypoints_per_frame", {{"mean", double(total) / double(col.frames.size())}, {"min", least}, {"max", most}}},
        {"failed_frames", col.failed},
        {"seconds", col.seconds}};
    if (!col.simulated.is_null()) j["simulated"] = col.simulated;
    return j;
}

// Every way the two columns differ, by design. Each can be switched off alone (surfvp surf's
// options, the chip's parameters); docs/table2.md says how.
Json differences(const Config& c) {
    const SurfWorkloadSettings s = surf_settings(c);
    return Json::array(
        {{{"what", "octaves"}, {"cpu", "4"}, {"fpga", "2 (the FHG's 2 octaves x 4 intervals)"}},
         {{"what", "filter sizes per octave"}, {"cpu", "5 (OpenCV's)"}, {"fpga", "4 (the paper's, in the FHG)"}},
         {{"what", "interpolation: the largest fitted offset kept"},
          {"cpu", "1 sample (OpenCV's)"},
          {"fpga", fmt::format("{} (surf.max_offset; the paper: 0.5)", s.max_offset)}},
         {{"what", "descriptor"},
          {"cpu", "M-SURF (OpenSURF's: overlapping sub-regions, two Gaussians)"},
          {"fpga", s.descriptor == surf::DescriptorKind::msurf
                       ? "M-SURF (surf.descriptor; the paper: Bay's SURF)"
                       : "SURF (Bay's: 4 x 4 sub-regions of 5 x 5 samples, one Gaussian; surf.descriptor)"}},
         {{"what", "Haar wavelets of orientation and descriptor"},
          {"cpu", "exact (sub-pixel sample positions)"},
          {"fpga", fmt::format("{} (surf.haar)", surf::haar_name(s.haar))}},
         {{"what", "determinants"},
          {"cpu", "float"},
          {"fpga", "integer, at the FHG's fixed-point widths (fhg.* precision parameters)"}},
         {{"what", "non-maximum suppression"},
          {"cpu", "3x3x3 in float"},
          {"fpga",
           "partial, in each 2x2 determinant block (LocalMaxFinder), re-checked in software over the integer "
           "determinants"}},
         {{"what", "threshold"},
          {"cpu", "calibrated on frame 0 with the CPU's settings"},
          {"fpga",
           "calibrated on frame 0 with 2 octaves (the float reference limited to the chip's octaves), in the FHG's "
           "units"}}});
}

// A cell none of whose pairs gave a ratio (each had fewer candidates than the measure needs)
// measured nothing: it is no 0.
bool measured(const Json& cell) { return cell.value("measured_pairs", size_t(1)) > 0; }

std::string figure(const Json& cell) {
    if (!measured(cell)) return fmt::format("not measured (0 of {} pairs)", cell["pairs"].get<size_t>());
    return fmt::format("{:.3f} ± {:.3f} ({})", cell["mean"].get<double>(), cell["spread"].get<double>(),
                       cell["pairs"].get<size_t>());
}

std::string row_label(const Json& row) {
    return fmt::format("{} | {}", row["limited_search"].get<bool>() ? "Y" : "N",
                       row["laplacian"].get<bool>() ? "Y" : "N");
}

void markdown_gap(std::string& md, const Json& gap, const char* measure, const char* title) {
    const size_t k = gap["gap"].get<size_t>();
    md += fmt::format("\n## Distinguishability, frames (i, i + {}), {}\n\n", k, title);
    const bool paper = gap["rows"][0].contains("paper"), best = gap["rows"][0].contains("fpga_best");
    md += "| limited search | Laplacian | CPU | FPGA | FPGA − CPU |";
    md += best ? " FPGA, best affordable software | best − CPU |" : "";
    md += paper ? " paper CPU | paper FPGA |" : "";
    md += "\n|---|---|---|---|---|" + std::string(best ? "---|---|" : "") + (paper ? "---|---|" : "") + "\n";
    for (const Json& row : gap["rows"]) {
        const Json& cpu = row["cpu"][measure];
        md += fmt::format("| {} | {} |", row_label(row), figure(cpu));
        for (const char* chip : {"fpga", "fpga_best"}) {
            if (!row.contains(chip)) continue;
            const Json& fpga = row[chip][measure];
            const double change = std::round((fpga["mean"].get<double>() - cpu["mean"].get<double>()) * 1000) / 1000;
            md += fmt::format(" {} | {} |", figure(fpga),
                              measured(cpu) && measured(fpga) ? fmt::format("{:+.3f}", change + 0.0)  // no -0.000
                                                              : std::string("-"));
        }
        if (paper)
            md += fmt::format(" {:.2f} | {:.2f} |", row["paper"]["cpu"].get<double>(),
                              row["paper"]["fpga"].get<double>());
        md += "\n";
    }
}

void markdown_contributions(std::string& md, const Json& lines) {
    const bool truth = lines[0].contains("ground_truth"), precision = lines[0].contains("precision");
    md +=
        "\n## What each difference costs\n\nThe float reference with the chip's software settings, one at a time and "
        "then "
        "together (the same threshold rule, each calibrated on its own frame 0); what remains between the last and the "
        "chip is the hardware's: integer determinants and block-wise suppression. Frames (i, i + 1), "
        "distinguishability "
        "with RANSAC F";
    md += truth ? " (ground truth in brackets)" : "";
    md += precision ? "; precision of frames 0 and 1 under the homography" : "";
    md += ".\n\n| | keypoints per frame | Y Y | Y N | N Y | N N |";
    md += precision ? " precision |\n|---|---|---|---|---|---|---|\n" : "\n|---|---|---|---|---|---|\n";
    for (const Json& line : lines) {
        md +=
            fmt::format("| {} | {:.1f} |", line["label"].get<std::string>(), line["keypoints_per_frame"].get<double>());
        for (size_t i = 0; i < 4; ++i) {
            const bool unmeasured = line.contains("ransac_measured") && !line["ransac_measured"][i].get<bool>();
            md += unmeasured ? std::string(" not measured") : fmt::format(" {:.3f}", line["ransac"][i].get<double>());
            if (truth) md += fmt::format(" ({:.3f})", line["ground_truth"][i].get<double>());
            md += " |";
        }
        if (precision) md += fmt::format(" {:.3f} |", line["precision"].get<double>());
        md += "\n";
    }
}

// A chip column's simulated time: its timed run's, or why there is none.
std::string simulated_time(const Json& c) {
    if (!c.contains("simulated")) return "-";
    const Json& t = c["simulated"];
    if (t.contains("error")) return "no timed run: " + t["error"].get<std::string>();
    return fmt::format("{:.1f} ms ({:.2f} frames/s{})", t["sim_time_s"].get<double>() * 1e3,
                       t["throughput_fps"].get<double>(), t["exit"] == kExitBroken ? ", broken" : "");
}

std::string table2_markdown(const Json& r) {
    std::string md = fmt::format("# Table II: {}\n\n{}\n\n", r["title"].get<std::string>(),
                                 r["scenario"]["description"].get<std::string>());
    md += fmt::format(
        "{} frames of {}x{} from `{}`. Each cell: mean ± standard deviation over the pairs (pairs); a pair "
        "without a measured ratio counts 0, as in the paper; a cell none of whose pairs gave a ratio says "
        "\"not measured\" and has no difference. Limited search: {:g} px.\n\n",
        r["frames"].get<size_t>(), r["image"]["width"].get<int>(), r["image"]["height"].get<int>(),
        r["source"].get<std::string>(), kLimitedSearchPx);
    md +=
        "| column | keypoints per frame | threshold | rule | failed frames | host seconds | the chip's simulated time "
        "|\n|---|---|---|---|---|---|---|\n";
    for (const auto& [name, c] : r["columns"].items()) {
        md += fmt::format("| {} | {:.1f} ({}..{}) | {:.6g} | {} | {} | {:.1f} s | {} |\n",
                          c["label"].get<std::string>(), c["keypoints_per_frame"]["mean"].get<double>(),
                          c["keypoints_per_frame"]["min"].get<size_t>(), c["keypoints_per_frame"]["max"].get<size_t>(),
                          c["threshold"].get<double>(), c["threshold_rule"].get<std::string>(),
                          c["failed_frames"].size(), c["seconds"].get<double>(), simulated_time(c));
    }
    md +=
        "\nThe FPGA column is a run of the chip in direct mode (the same driver, cores and software without "
        "SystemC): its keypoints are the VP's byte for byte. Its run folder is `fpga/`; the CPU's keypoint files are "
        "in `cpu/keypoints/`. \"host seconds\" is this machine's time to compute each column, not the chip's; the "
        "chip's simulated time is a timed run of the same frames (`surfvp run`, the verdict's analyses off), since "
        "direct mode simulates none.\n";
    if (r["columns"].contains("fpga_best"))
        md += fmt::format(
            "\nThe chip with its best affordable software (`{}`, `fpga_best/`): the same chip and driver, with the CPU "
            "stage's settings that `surfvp quality-budget` found the most distinguishable while the CPU alone still "
            "holds 10 frames/s at 1024x768 (docs/quality_budget.md).\n",
            fmt::join(r["best_software"].get<std::vector<std::string>>(), "`, `"));
    for (const Json& gap : r["gaps"]) {
        markdown_gap(md, gap, "ransac", "F from RANSAC (the paper's measure)");
        if (gap["rows"][0]["cpu"].contains("ground_truth"))
            markdown_gap(md, gap, "ground_truth", "F from the camera poses");
    }
    if (r.contains("homography")) {
        md +=
            "\n## Frames 0 and 1 under the homography\n\nOn a planar scene every F = [e']x H fits the true "
            "correspondences, so RANSAC's F accepts more than the homography does: precision is the figure to compare "
            "here, not the distinguishability above.\n\n| column | keypoints | repeatability | precision (correct / "
            "candidates) |\n|---|---|---|---|\n";
        for (const auto& [name, h] : r["homography"].items()) {
            md += fmt::format("| {} | {} / {} | {:.3f} | {:.3f} ({} / {}) |\n", name, h["keypoints"][0].get<size_t>(),
                              h["keypoints"][1].get<size_t>(), h["repeatability"].get<double>(),
                              h["precision"].get<double>(), h["precision_correct"].get<size_t>(),
                              h["precision_candidates"].get<size_t>());
        }
    }
    if (r.contains("contributions")) markdown_contributions(md, r["contributions"]);
    md +=
        "\nThe paper's columns are its own figures on its own 1500-image data set (not available): a reference to "
        "read these against, not a result of this run.\n\n## What the columns differ in\n\n| | CPU | FPGA "
        "|\n|---|---|---|\n";
    for (const Json& d : r["differences"])
        md += fmt::format("| {} | {} | {} |\n", d["what"].get<std::string>(), d["cpu"].get<std::string>(),
                          d["fpga"].get<std::string>());
    return md;
}

// Timed runs of the chip columns' scenarios (forked: the SystemC kernel elaborates once per
// process), each giving its simulated time and frame rate.
std::vector<Json> timed_runs(const std::vector<Config>& configs, const fs::path& scratch) {
    std::vector<Json> out(configs.size());
    {
        for (const Config& c : configs) Resimulation::prepare(c);
        Resimulation engine(0, scratch);
        for (size_t i = 0; i < configs.size(); ++i) {
            Config c = configs[i];
            apply_overrides(c, kWithoutVerdictAnalyses);
            engine.submit(
                c, [&out, i](const Json& r) { out[i] = r; },
                [](const Json& r) -> Json {
                    return {{"sim_time_s", r.value("sim_time_s", 0.0)},
                            {"throughput_fps", r.value("throughput_fps", 0.0)},
                            {"exit", exit_code_of(r)}};
                });
        }
        engine.run([](size_t, size_t) {});
    }
    fs::remove_all(scratch);
    cv::setNumThreads(-1);  // prepare stopped OpenCV's threads for the children; the measures want them
    return out;
}

// The scenario with the chip's best affordable software, unless it runs that already.
std::optional<Config> with_best_software(const Config& config) {
    Config best = config;
    apply_overrides(best, kBestAffordableSoftware);
    for (const std::string& set : kBestAffordableSoftware) {
        const std::string key = set.substr(0, set.find('='));
        if (best.value(key) != config.value(key)) return best;
    }
    return std::nullopt;
}

void print_summary(const Json& r, const fs::path& dir) {
    const Json& gap = r["gaps"][0];
    auto mean = [](const Json& cell) {
        return measured(cell) ? fmt::format("{:.3f}", cell["mean"].get<double>()) : std::string("not measured");
    };
    for (const Json& row : gap["rows"])
        std::fprintf(
            stderr, "surfvp: table2: limited %s  Laplacian %s  CPU %s  FPGA %s%s\n",
            row["limited_search"].get<bool>() ? "Y" : "N", row["laplacian"].get<bool>() ? "Y" : "N",
            mean(row["cpu"]["ransac"]).c_str(), mean(row["fpga"]["ransac"]).c_str(),
            row.contains("fpga_best") ? ("  FPGA best software " + mean(row["fpga_best"]["ransac"])).c_str() : "");
    std::fprintf(stderr, "surfvp: table2: %s: report in %s\n", r["title"].get<std::string>().c_str(),
                 (dir / "report.md").string().c_str());
}

}  // namespace

int table2_command(const Table2Options& o) {
    const Config config = load_scenario(resolve_scenario(o.scenario), o.sets);
    const SurfWorkloadSettings s = surf_settings(config);
    if (run_settings(config).workload != "surf")
        throw ConfigError(
            fmt::format("{}: table2 needs a SURF scenario (run.workload: surf)", config.where("run.workload")));
    if (s.frames < 2)
        throw ConfigError(fmt::format("{}: table2 compares frame pairs: surf.frames must be at least 2",
                                      config.where("surf.frames")));
    if (!config.faults.empty())
        throw ConfigError(fmt::format("{}: faults: table2 runs the chip without time; run the scenario without faults",
                                      config.faults.front().origin));
    check_scenario(config);
    const Geometry geometry = read_geometry(config);
    OutputFolder out(o.out.empty() ? fs::path("traces") / config.name : fs::path(o.out),
                     {"cpu", "fpga", "fpga_best", "report.json", "report.md", "config.yaml"});
    const fs::path staging = out.staging();
    Json r;
    try {
        const std::vector<Variant> float_variants = variants(config);
        // Steps: the float reference, the chip, the measures, each other float variant.
        ProgressLine progress(o.quiet, config.name, 0.0, 0.5, 5.0);
        size_t step = 0;
        const size_t steps = float_variants.size() + 4;
        auto next = [&](const std::string& what) { progress.steps(step++, steps, "steps", false, ": " + what); };
        next("the float reference");
        Column cpu = cpu_column(config, float_variants[0], staging / "cpu");
        next("the chip (direct mode)");
        Column fpga = fpga_column(config, staging / "fpga", cpu.sizes);
        std::vector<Column> columns{std::move(cpu), std::move(fpga)};
        std::vector<Config> timed{config};  // the chip columns' scenarios
        if (const std::optional<Config> best = with_best_software(config)) {
            next("the chip with its best affordable software");
            columns.push_back(fpga_column(*best, staging / "fpga_best", columns[0].sizes));
            columns.back().name = "fpga_best", columns.back().label = "FPGA, best affordable software";
            timed.push_back(*best);
        }
        next("the chip's simulated time (timed runs)");
        {
            const std::vector<Json> times = timed_runs(timed, staging / ".timed");
            for (size_t i = 0; i < times.size(); ++i) columns[i + 1].simulated = times[i];
        }
        next("distinguishability of the columns");
        const Json fpga_report = Json::parse(std::ifstream(staging / "fpga" / "report.json"));
        r["surfvp_version"] = SURFVP_VERSION;
        r["scenario"] = {{"name", config.name}, {"file", config.file}, {"description", config.description}};
        r["source"] = s.source;
        // A source given on the command line is what the table measures: it titles the table,
        // and the scenario's description (of its own source) is said to be the settings'.
        const bool own_source = config.source_of("surf.source") == "--set";
        const fs::path source(s.source);
        const std::string shown = (source.parent_path().filename() / source.filename()).string();
        r["title"] = own_source ? fmt::format("{} (with {}'s settings)", shown, config.name) : config.name;
        if (own_source)
            r["scenario"]["description"] =
                fmt::format("`{}` through the chip, with the settings of scenario {}.", s.source, config.name);
        r["frames"] = s.frames;
        r["image"] = fpga_report["image"];
        r["chip_run_passed"] = fpga_report["passed"];
        r["chip_run_broken"] = fpga_report["broken"];
        r["columns"] = Json::object();
        for (const Column& col : columns) r["columns"][col.name] = column_summary(col);
        if (columns.size() > 2) r["best_software"] = kBestAffordableSoftware;
        std::vector<size_t> gaps{1};
        if (const uint64_t gap = eval_settings(config).gap; gap > 1 && gap < s.frames) gaps.push_back(gap);
        std::vector<Measures> measures;
        for (const Column& col : columns) measures.push_back(measure(col, gaps, geometry));
        r["gaps"] = Json::array();
        for (size_t gap : gaps) r["gaps"].push_back(gap_table(columns, measures, gap));
        for (size_t c = 0; c < columns.size() && geometry.homography; ++c)
            r["homography"][columns[c].name] = *measures[c].homography;
        r["differences"] = differences(config);
        r["contributions"] = Json::array({quality_line(columns[0], measures[0])});
        for (size_t i = 1; i < float_variants.size(); ++i) {
            next(float_variants[i].name);
            r["contributions"].push_back(quality_line(cpu_column(config, float_variants[i]), geometry));
        }
        progress.end();
        for (size_t c = 1; c < columns.size(); ++c) r["contributions"].push_back(quality_line(columns[c], measures[c]));
        write_file_atomically(staging / "report.json", r.dump(2) + "\n");
        write_file_atomically(staging / "report.md", table2_markdown(r));
        write_file_atomically(staging / "config.yaml", config.to_yaml());
        out.publish();
        if (!o.quiet) print_summary(r, out.folder());
        // The paper's chip answers; the best software's chip only when it broke.
        return columns.size() > 2 && columns[2].exit_code == kExitBroken ? kExitBroken : columns[1].exit_code;
    } catch (const EnvironmentError& e) {
        throw EnvironmentError(
            fmt::format("{}; what was in {} before is as it was", out.as_published(e.what()), out.folder().string()));
    }
}

}  // namespace surfvp
