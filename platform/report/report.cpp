#include "platform/report/report.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <stdexcept>

#include "platform/report/correlation.h"
#include "platform/report/run_summary.h"
#include "platform/report/section_statistics.h"
#include "platform/report/statistics_json.h"

namespace surfvp {
namespace {

std::string ms(double seconds) { return fmt::format("{:.3f} ms", seconds * 1e3); }
std::string percent(double share) { return fmt::format("{:.1f} %", share * 100); }

// MiB, or bytes where MiB would read as 0 (register traffic).
std::string mib(double bytes) {
    return bytes < 10240 ? fmt::format("{:.0f} B", bytes) : fmt::format("{:.2f} MiB", bytes / (1024.0 * 1024.0));
}

// Each path's traffic (in total, per frame, MB/s over the run) and each master that used the bus.
void bus_section(std::string& md, const std::string& name, const nlohmann::ordered_json& node, double seconds,
                 double frames) {
    const Shown bus(node, section_statistics("Buses"));
    md += fmt::format("\n### {} ({} bit at {} MHz)\n\n", name, bus.count("width_bits"), bus.number("clock_hz") / 1e6);
    md += "| path | bursts | bytes | per frame | MB/s | busy | utilisation |\n|---|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string path : {"read", "write"}) {
        const double bytes = bus.number(path + ".bytes");
        md += fmt::format("| {} | {} | {} | {} | {:.1f} | {} | {} |\n", path, bus.count(path + ".bursts"), mib(bytes),
                          mib(bytes / frames), seconds > 0 ? bytes / seconds / 1e6 : 0.0,
                          ms(bus.number(path + ".busy_s")), percent(bus.number(path + ".utilisation")));
    }
    md +=
        "\n| master | bursts | read | written | per frame (read + written) | busy | waited | mean wait | max wait | "
        "bursts by wait (bus cycles) | errors |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n";
    for (const auto& [master, m] : bus.each("masters")) {
        if (m.count("bursts") == 0 && m.count("errors") == 0) continue;  // idle: no row
        std::string histogram;
        for (const auto& [bin, n] : m["bursts_by_wait_cycles"].items())
            if (n.get<uint64_t>())
                histogram += fmt::format("{}{}: {}", histogram.empty() ? "" : ", ", bin, n.get<uint64_t>());
        const double bursts = std::max(1.0, m.number("bursts"));
        const double read = m.number("bytes_read"), written = m.number("bytes_written");
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {:.1f} ns | {:.1f} ns | {} | {} |\n", master,
                          m.count("bursts"), mib(read), mib(written), mib((read + written) / frames),
                          ms(m.number("busy_s")), ms(m.number("wait_s")), m.number("wait_s") / bursts * 1e9,
                          m.number("max_wait_s") * 1e9, histogram, m.count("errors"));
    }
}

// The DDR: bytes over its ports in total and per frame, MB/s, busy; each port's wait.
std::string memory_section(const nlohmann::ordered_json& node, double seconds, double frames) {
    const Shown mem(node, section_statistics("DDR"));
    const double read = mem.number("bytes_read"), written = mem.number("bytes_written");
    std::string md = fmt::format(
        "\n### DDR\n\n{} read, {} written ({} per frame, {:.1f} MB/s); DRAM busy {} ({}).\n\n"
        "| port | reads | writes | read | written | waited |\n|---|---:|---:|---:|---:|---:|\n",
        mib(read), mib(written), mib((read + written) / frames), seconds > 0 ? (read + written) / seconds / 1e6 : 0.0,
        ms(mem.number("busy_s")), percent(mem.number("utilisation")));
    for (const auto& [port, p] : mem.each("ports"))
        md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", port, p.count("reads"), p.count("writes"),
                          mib(p.number("bytes_read")), mib(p.number("bytes_written")), ms(p.number("wait_s")));
    return md;
}

// Per resource: its frame period, busy, each wait, idle, and what it alone would allow.
std::string time_table(const nlohmann::ordered_json& table, const nlohmann::ordered_json& periods, bool budget) {
    std::string md = fmt::format(
        "\nWhere each resource's frame goes, in ms per frame over the whole run: busy (its own work) + each wait + "
        "idle = "
        "its period, the simulated time per frame ({:.2f} ms, filling and draining the pipeline included; an "
        "accelerator "
        "pair's is the frames it takes, pairs x that). Its load is its busy time against the steady-state period "
        "({:.2f} ms, 1 / frames per second); what it alone would allow is 1 / its busy time per frame. The blocks' own "
        "statistics count the same way: `fhg.utilisation` is the FHG's busy share of the run.\n\n"
        "| resource | period | busy | waiting | idle | busy share | load | alone | {}",
        periods["run"].get<double>(), periods["steady"].get<double>(),
        budget ? "slack |\n|---|---:|---:|---|---:|---:|---:|---:|---:|\n"
               : "\n|---|---:|---:|---|---:|---:|---:|---:|\n");
    for (const auto& [name, row] : table.items()) {
        std::string waits;
        for (const auto& [cause, ms] : row["waits_ms"].items())
            if (ms.get<double>() >= 0.005)
                waits += fmt::format("{}{} {:.2f}", waits.empty() ? "" : "; ", cause, ms.get<double>());
        const std::string alone =
            row["alone_fps"].is_null() ? "-" : fmt::format("{:.2f} frames/s", row["alone_fps"].get<double>());
        md += fmt::format("| {} | {:.2f} | {:.2f} | {} | {:.2f} | {} | {} | {} |", name, row["period_ms"].get<double>(),
                          row["busy_ms"].get<double>(), waits.empty() ? "-" : waits, row["idle_ms"].get<double>(),
                          percent(row["busy_share"]), percent(row["load"]), alone);
        if (budget)
            md += row.contains("slack") ? fmt::format(" {:+.1f} % |", 100 * row["slack"].get<double>()) : " - |";
        md += "\n";
    }
    return md;
}

// Each frame's keypoint count (the workload's per-frame list), smallest first.
std::vector<double> sorted_keypoints(const nlohmann::ordered_json& per_frame) {
    std::vector<double> kp;
    for (const auto& f : per_frame) kp.push_back(f["keypoints"].get<double>());
    std::sort(kp.begin(), kp.end());
    return kp;
}

// The thresholds the frames ran with, when they were not all one (libSSA2's keypoint-count control).
std::string threshold_range(const nlohmann::ordered_json& per_frame) {
    double least = 0, most = 0;
    bool any = false;
    for (const auto& f : per_frame) {
        if (!f.contains("threshold")) continue;
        const double t = f["threshold"].get<double>();
        least = any ? std::min(least, t) : t, most = any ? std::max(most, t) : t, any = true;
    }
    return any && least != most ? fmt::format("; threshold per frame {:.3f} to {:.3f}", least, most) : "";
}

std::string median_keypoints(const nlohmann::ordered_json& r) {
    if (!r.contains("workload") || !r["workload"].contains("per_frame")) return "-";
    const std::vector<double> kp = sorted_keypoints(r["workload"]["per_frame"]);
    return kp.empty() ? "-" : fmt::format("{:.0f}", kp[kp.size() / 2]);
}

// The figures behind the verdict: rate, budget, latency, keypoints, threshold, where the time goes.
std::string frames_section(const nlohmann::ordered_json& r) {
    std::string md = "\n## Frames: the figures behind the verdict\n\n| | |\n|---|---:|\n";
    md += fmt::format("| image | {} x {} |\n", r["image"]["width"].get<int>(), r["image"]["height"].get<int>());
    md += fmt::format("| frames done | {} of {} |\n", r["frames_done"].get<size_t>(), r["frames"].get<size_t>());
    md += fmt::format("| throughput | **{:.2f} frames/s** |\n", r["throughput_fps"].get<double>());
    if (!r["budget"].is_null())
        md += fmt::format("| budget | {:.2f} frames/s: **{}** |\n", r["budget"]["fps"].get<double>(),
                          r["budget"]["met"].get<bool>() ? "met" : "MISSED");
    md += fmt::format("| latency (hardware start to descriptors) | {:.2f} ms |\n", r["latency_ms"].get<double>());
    md += fmt::format("| keypoints per frame | {:.1f} mean; min {}, median {}, max {} |\n",
                      r["keypoints_per_frame"].get<double>(), r["keypoints_per_frame_range"][0].dump(),
                      median_keypoints(r), r["keypoints_per_frame_range"][1].dump());
    if (r.contains("threshold_rule"))
        md += fmt::format("| determinant threshold | {:.3f}: {} |\n", r["threshold"].get<double>(),
                          r["threshold_rule"].get<std::string>());
    md += fmt::format(
        "| software per keypoint | {:.1f} us ({:.0f} CPU cycles, its line-fill stalls included; the CPU "
        "section's cycles of computation leave them out) |\n",
        r["software_time_per_keypoint_us"].get<double>(), r["software_cycles_per_keypoint"].get<double>());
    if (r.contains("limit")) {
        md += fmt::format("| limited by | **{}** ({}) |\n", r["limit"]["resource"].get<std::string>(),
                          r["limit"]["cause"].get<std::string>());
        md += fmt::format("\n**What limits the frame rate:** {}.\n", r["limit"]["reason"].get<std::string>());
        md += time_table(r["time_per_frame"], r["time_per_frame_period_ms"], !r["budget"].is_null());
    }
    md +=
        "\nMean phase times (integral image and determinants: from the task's hardware start, in parallel; "
        "descriptors: from the determinants' end to the last descriptor):\n\n| phase | ms |\n|---|---:|\n";
    for (const auto& [name, ms] : r["phases_ms"].items())
        md += fmt::format("| {} | {:.2f} |\n", name, ms.get<double>());
    return md;
}

std::string fps_or_dash(const nlohmann::ordered_json& side) {
    if (side.contains("error")) return "invalid";
    return side["fps"].is_null() ? "(current)" : fmt::format("{:.2f}", side["fps"].get<double>());
}

// A whole-run check: met; relieved, with the rate now held below the budget by the next limit;
// for a resource with headroom, the rate its step started from kept; or missed.
std::string check_outcome(const nlohmann::ordered_json& c) {
    if (!c["met"].get<bool>()) return "MISSED";
    if (c.value("budget_met", true)) return "met";
    if (c.value("goal", "") == "keep") return "the rate kept within 0.1 %";
    return fmt::format("relieved (now held below the budget by {})",
                       c["limit"].is_null() ? "?" : c["limit"].get<std::string>());
}

// One break-even search as a table row: "up to" or "down to" the value, its rate there, its
// whole-run check.
std::string break_even_row(const nlohmann::ordered_json& b) {
    if (b["value"].is_null())
        return fmt::format("| `{}` | {} | none | - | {} |\n", b["parameter"].get<std::string>(),
                           b["default"].get<std::string>(), b["note"].get<std::string>());
    const auto& c = b["check"];
    const std::string check = c.is_null() ? "-"
                              : c.contains("error")
                                  ? "failed: " + c["error"].get<std::string>()
                                  : fmt::format("{:.3f} frames/s over {} frames: {}", c["fps"].get<double>(),
                                                c["frames"].get<uint64_t>(), check_outcome(c));
    return fmt::format("| `{}` | {} | **{} {}** | {:.3f} | {} |\n", b["parameter"].get<std::string>(),
                       b["default"].get<std::string>(), b.value("searched", "up") + " to",
                       b["value"].get<std::string>(), b["fps"].get<double>(), check);
}

// Each limit in turn: what limits, its headroom, what was relieved to reach it, its break-even.
std::string chain_section(const nlohmann::ordered_json& chain) {
    std::string md =
        "\nThe chain of limits: each limit's break-even (the value that just meets the budget, found by "
        "re-simulation and checked by a run of the whole scenario), then the limit relieved at it and the next "
        "one named with its headroom (the frame rate it alone would allow against the budget).\n";
    for (size_t k = 0; k < chain.size(); ++k) {
        const auto& step = chain[k];
        std::vector<std::string> relieved;
        for (const auto& r : step["relieved"])
            relieved.push_back(
                fmt::format("`{}` = {}", r["parameter"].get<std::string>(), r["value"].get<std::string>()));
        const std::string headroom =
            step["headroom"].is_null()
                ? ""
                : fmt::format(", alone {:.2f} frames/s, headroom {:+.1f} %", step["alone_fps"].get<double>(),
                              100 * step["headroom"].get<double>());
        md += fmt::format("\n{}. **{}** ({}{}){}:\n\n", k + 1, step["resource"].get<std::string>(),
                          step["cause"].get<std::string>(), headroom,
                          relieved.empty() ? "" : fmt::format(", with {}", fmt::join(relieved, " and ")));
        if (step.value("searched", true))
            md += "| parameter | now | break-even | frames/s there | check |\n|---|---|---|---:|---|\n";
        if (!step.value("searched", true)) {
            md += "The chain ends here: this limit is named with its headroom; its break-even is not searched.\n";
            continue;
        }
        if (step["break_even"].empty()) md += "| - | - | no parameter of this cause to search | - | - |\n";
        for (const auto& b : step["break_even"]) md += break_even_row(b);
    }
    return md;
}

// One-at-a-time rows (the band's unknowns, or what a review can change): what flips the
// verdict, what the platform refused, then the twelve largest effects.
std::string band_rows(const nlohmann::ordered_json& band, const char* what) {
    std::string md;
    if (!band["flipping"].empty())
        md += fmt::format("Values that flip the verdict: {}.\n",
                          fmt::join(band["flipping"].get<std::vector<std::string>>(), ", "));
    if (!band["failed_points"].empty())
        md += fmt::format("Values the platform refused (see report.json): {}.\n",
                          fmt::join(band["failed_points"].get<std::vector<std::string>>(), ", "));
    md += fmt::format("\n| {} | now | low | frames/s | high | frames/s | effect |\n|---|---|---|---:|---|---:|---:|\n",
                      what);
    size_t shown = 0;
    for (const auto& a : band["axes"]) {
        if (shown++ == 12) break;
        md += fmt::format("| `{}` | {} | {} | {} | {} | {} | {:.2f} |\n", a["parameter"].get<std::string>(),
                          a["value"].get<std::string>(), a["low"]["value"].get<std::string>(), fps_or_dash(a["low"]),
                          a["high"]["value"].get<std::string>(), fps_or_dash(a["high"]), a["effect_fps"].get<double>());
    }
    if (band["axes"].size() > 12)
        md += fmt::format("\n({} more with smaller effects in report.json.)\n", band["axes"].size() - 12);
    return md;
}

// The unknowns jointly: the frame rate's percentiles, the chance of meeting the budget, and
// which unknowns its variance comes from.
std::string doubt_section(const nlohmann::ordered_json& d) {
    if (!d.contains("fps"))
        return fmt::format(
            "\nThe joint sample of the unknowns gave no rate ({} of {} points failed; see report.json).\n",
            d["failed_points"].size(), d["points"].get<size_t>());
    const auto& f = d["fps"];
    std::string md = fmt::format(
        "\nThe doubt, jointly: the {} unknowns about the chip sampled together over their bands ({} points, a Latin "
        "hypercube, {}-frame runs): **{:.2f} frames/s at the 5th percentile, {:.2f} at the median, {:.2f} at the "
        "95th** "
        "(all points {:.2f} to {:.2f}){}.{}\n",
        d["unknowns"].get<size_t>(), d["points"].get<size_t>(), d["frames"].get<unsigned>(), f["p5"].get<double>(),
        f["p50"].get<double>(), f["p95"].get<double>(), f["min"].get<double>(), f["max"].get<double>(),
        d.contains("probability_met")
            ? fmt::format("; **the budget is met with probability {:.0f} %**", 100 * d["probability_met"].get<double>())
            : "",
        d["failed_points"].empty() ? "" : fmt::format(" {} points failed (report.json).", d["failed_points"].size()));
    md += fmt::format(
        "\nWhich unknowns the frame rate's variance comes from (Sobol indices of a surrogate fitted to the points, "
        "R^2 = {:.3f}: {}): first-order is the share of the variance an unknown explains alone, total adds "
        "its interactions with the others.\n\n| unknown | first-order | total |\n|---|---:|---:|\n",
        d["surrogate"]["r2"].get<double>(), d["surrogate"]["method"].get<std::string>());
    size_t shown = 0;
    for (const auto& s : d["sensitivity"]) {
        if (shown++ == 8) break;
        md += fmt::format("| `{}` | {:.3f} | {:.3f} |\n", s["parameter"].get<std::string>(),
                          s["first_order"].get<double>(), s["total"].get<double>());
    }
    return md;
}

// The verdict and its doubt: the statement, the break-even values, the assumption band.
std::string verdict_section(const nlohmann::ordered_json& v) {
    std::string md = "\n## Verdict\n";  // its statement heads the report
    if (v.contains("limit"))
        md += fmt::format("\nLimited by {}: {}.\n", v["limit"]["resource"].get<std::string>(),
                          v["limit"]["reason"].get<std::string>());
    if (v.contains("chain")) md += chain_section(v["chain"]);
    if (v.contains("doubt")) md += doubt_section(v["doubt"]);
    if (v.contains("band")) {
        const auto& band = v["band"];
        md += fmt::format(
            "\nThe unknowns one at a time ({} of them, each at its low and its high): **{:.2f} to {:.2f} frames/s** "
            "(the run's rate plus each change's effect, measured in {}-frame runs against a reference of {:.3f} "
            "frames/s).\n",
            band["axes"].size(), band["low_fps"].get<double>(), band["high_fps"].get<double>(),
            band["frames"].get<unsigned>(), band["reference_fps"].get<double>());
        md += band_rows(band, "unknown") + "\n![tornado](tornado.svg)\n";
    }
    if (v.contains("changes") && !v["changes"]["axes"].empty())
        md +=
            "\nWhat a review can change (design choices and the workload, each at its low and its high, one at a time; "
            "not part of the doubt):\n" +
            band_rows(v["changes"], "setting");
    if (v.contains("software")) {
        md +=
            "\nSettings the CPU's time rests on, the software's and the FPU's (each alone, the rest as the scenario; "
            "CPU time from the "
            "calibrated PPC440 cost model, sw/cpu_cost/calibration.md):\n\n"
            "| setting | frames/s | CPU ms per frame | CPU alone, frames/s | keypoints per frame | limit |\n"
            "|---|---:|---:|---:|---:|---|\n";
        for (const auto& row : v["software"]) {
            if (row.contains("error")) {
                md += fmt::format("| {} | refused: {} | | | | |\n", row["setting"].get<std::string>(),
                                  row["error"].get<std::string>());
                continue;
            }
            md += fmt::format("| {} | {:.2f} | {:.1f} | {:.2f} | {:.0f} | {} |\n", row["setting"].get<std::string>(),
                              row["fps"].get<double>(), row["cpu_ms_per_frame"].get<double>(),
                              row["cpu_alone_fps"].get<double>(), row["keypoints_per_frame"].get<double>(),
                              row["limit"].is_null() ? "-" : row["limit"].get<std::string>());
        }
    }
    return md;
}

// The accelerators (summed over the pairs): the FHG's schedule and where its time went, the
// IIG's stalls.
std::string accelerators_section(const nlohmann::ordered_json& r) {
    std::string md;
    if (r.contains("fhg") && r["fhg"].contains("schedules")) {
        const Shown f(r["fhg"], section_statistics("SSA FHG"));
        const auto& sc = r["fhg"]["schedules"];
        const auto& basic = sc["basic"];
        md += fmt::format(
            "\n## SSA FHG\n\n**{} cycles per determinant block** (limited by the {}; schedule `{}`, line FIFO `{}`: "
            "basic "
            "{}, improved {}). The basic script is {:+.1f} % over the paper's optimal state (its note 4: the read "
            "buses busy "
            "every cycle with the {} words it carries, {} cycles) and {:+.1f} % over the structural bound ({} cycles, "
            "set by "
            "{}). Holding frames {}: computing (busy) {}, waiting for integral lines {}, for the determinant writer "
            "{}. "
            "Line FIFO high-water {} lines; maxima FIFO high-water {} words; {} candidates, {} dropped; {} errors.\n",
            f.count("cycles_per_block"), f.text("block_limit"), sc["scheduler"].get<std::string>(),
            sc["machine"]["line_fifo"].get<std::string>(), basic["cycles_per_block"].get<unsigned>(),
            sc["improved"]["cycles_per_block"].get<unsigned>(), 100 * basic["idle_bus_overhead"].get<double>(),
            basic["words"].get<int>(), basic["busy_bus_cycles"].get<int>(), 100 * basic["overhead"].get<double>(),
            sc["optimal"]["cycles_per_block"].get<unsigned>(), sc["optimal"]["limit"].get<std::string>(),
            ms(f.number("busy_s")), ms(f.number("computing_s")), ms(f.number("waiting_for_lines_s")),
            ms(f.number("waiting_for_writer_s")), f.count("line_fifo_high_water"), f.count("maxima_fifo_high_water"),
            f.count("candidates"), f.count("candidates_dropped"), f.count("errors"));
    }
    if (r.contains("iig") && r["iig"].contains("computing_s")) {
        const Shown i(r["iig"], section_statistics("SSA IIG"));
        md += fmt::format(
            "\n## SSA IIG\n\nHolding frames {}: computing (busy) {}, waiting for the image {}, blocked by its integral "
            "write {}, by PixelBus "
            "back-pressure {} (its sender stalled {}); {} errors.\n",
            ms(i.number("busy_s")), ms(i.number("computing_s")), ms(i.number("waiting_for_image_s")),
            ms(i.number("blocked_by_write_s")), ms(i.number("blocked_by_pixelbus_s")), ms(i.number("send_stalled_s")),
            i.count("errors"));
    }
    return md;
}

// The CPU's software stage: what became of the candidates, where its cycles went (by step and
// by unit of work, from the calibrated cost model), what it executed, and its L1.
std::string software_stage_section(const nlohmann::ordered_json& st) {
    const double keypoints = std::max(1.0, st["keypoints"].get<double>());
    const auto& rejected = st["rejected"];
    std::string md = fmt::format(
        "\n### Software stage\n\n{} candidates from the maxima FIFOs: {} keypoints; rejected {} not a maximum of "
        "its 26 neighbours, {} by the interpolation, {} at the border.\n\n| step | cycles | per keypoint | share |\n"
        "|---|---:|---:|---:|\n",
        st["candidates"].get<uint64_t>(), st["keypoints"].get<uint64_t>(), rejected["not_maximum"].get<uint64_t>(),
        rejected["interpolation"].get<uint64_t>(), rejected["border"].get<uint64_t>());
    const double total = std::max(1.0, st["total_cycles"].get<double>());
    for (const auto& [step, cycles] : st["cycles_by_step"].items())
        md += fmt::format("| {} | {:.0f} | {:.0f} | {} |\n", step, cycles.get<double>(),
                          cycles.get<double>() / keypoints, percent(cycles.get<double>() / total));
    md += "\n| unit of work | count | cycles |\n|---|---:|---:|\n";
    for (const auto& [unit, u] : st["cycles_by_unit"].items())
        if (unit != "cache_miss")
            md += fmt::format("| {} | {} | {:.0f} |\n", unit, u["count"].get<uint64_t>(), u["cycles"].get<double>());
    std::string classes;
    for (const auto& [cls, n] : st["instructions_by_class"].items())
        classes += fmt::format("{}{} {}", classes.empty() ? "" : ", ", cls, n.get<uint64_t>());
    const auto& cal = st["calibration"];
    const auto& l1 = st["dcache"];
    md += fmt::format(
        "\nPPC440 instructions: {} ({:.0f} per keypoint; {}), {} calls into libm. Prices from the calibration of this "
        "code "
        "built with `{} {}` under `{}`, fitted on {} (sw/cpu_cost/calibration.md). L1 data cache: {} line accesses, "
        "hit "
        "rate {}, {} fills (timed on the memory path, under CPU above).\n",
        st["instructions"].get<uint64_t>(), st["instructions"].get<double>() / keypoints, classes,
        st["libm_calls"].get<uint64_t>(), cal.value("toolchain", "?"), cal.value("flags", "?"), cal.value("iss", "?"),
        cal.value("fitted_on", "?"), l1["accesses"].get<uint64_t>(), percent(l1["hit_rate"]),
        l1["misses"].get<uint64_t>());
    if (st.contains("fpu")) {
        const auto& fpu = st["fpu"];
        const double work = fpu["work_cycles_per_keypoint"], other = fpu["other_work_cycles_per_keypoint"];
        md += fmt::format(
            "\nFPU: the {}-precision APU FPU (`fpu.precision`). The {}-precision one would take {:.0f} cycles of work "
            "a "
            "keypoint against {:.0f} ({:+.1f} %), fills aside (sw/cpu_cost/README.md: one stream, two FPUs).\n",
            fpu["precision"].get<std::string>(), fpu["other_precision"].get<std::string>(), other, work,
            work > 0 ? 100 * (other / work - 1) : 0.0);
    }
    return md;
}

// A workload's scalars as they are; its per-frame list in frames.csv; its stage below.
// A value as words for a table cell: an object as "key value, ...", nested in parentheses,
// numbers to four digits; never JSON.
std::string plain_text(const nlohmann::ordered_json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
    if (v.is_number()) return fmt::format("{:.4g}", v.get<double>());
    if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
    if (v.is_null()) return "-";
    std::vector<std::string> parts;
    for (const auto& [key, item] : v.items()) {
        const std::string text = item.is_structured() ? "(" + plain_text(item) + ")" : plain_text(item);
        parts.push_back(v.is_object() ? key + " " + text : text);
    }
    return fmt::format("{}", fmt::join(parts, ", "));
}

std::string workload_section(const nlohmann::ordered_json& w) {
    std::string md = "\n## Workload\n\n| | |\n|---|---|\n";
    for (const auto& [key, value] : w.items()) {
        if (key == "software_stage" || (value.is_object() && value.empty())) continue;
        if (key == "per_frame") {
            const std::vector<double> kp = sorted_keypoints(value);
            if (!kp.empty())
                md += fmt::format(
                    "| frames | {} in `frames.csv`; keypoints per frame min {:.0f}, median {:.0f}, max {:.0f}{} |\n",
                    kp.size(), kp.front(), kp[kp.size() / 2], kp.back(), threshold_range(value));
            continue;
        }
        md += fmt::format("| {} | {} |\n", key, plain_text(value));
    }
    return md;
}

// Numbered files as one pattern: keypoints/frame_0000.surf ... -> keypoints/frame_NNNN.surf (20 files).
std::string files_section(const nlohmann::ordered_json& outputs) {
    std::vector<std::pair<std::string, size_t>> patterns;
    for (const auto& f : outputs) {
        std::string name = f.get<std::string>();
        for (char& c : name)
            if (c >= '0' && c <= '9') c = 'N';
        if (!patterns.empty() && patterns.back().first == name)
            ++patterns.back().second;
        else
            patterns.emplace_back(name, 1);
    }
    std::string md = "\n## Files\n\n";
    for (const auto& [name, n] : patterns)
        md += n > 1 ? fmt::format("- `{}` ({} files)\n", name, n) : fmt::format("- `{}`\n", name);
    return md;
}

}  // namespace

std::string frames_csv(const nlohmann::ordered_json& per_frame) {
    std::string csv;
    for (const auto& f : per_frame) {
        if (csv.empty()) {
            for (const auto& [key, value] : f.items()) csv += (csv.empty() ? "" : ",") + key;
            csv += "\n";
        }
        std::string row;
        for (const auto& [key, value] : f.items()) row += (row.empty() ? "" : ",") + value.dump();
        csv += row + "\n";
    }
    return csv;
}

namespace {

// One line at the top: the rate against the budget and what limits it, or why the run broke.
std::string headline(const nlohmann::ordered_json& r) {
    const std::string answer = answer_line(r);
    if (answer.empty()) return "";
    return fmt::format("**{}{}.**\n\n", r.value("broken", false) ? "The run broke: " : "", answer);
}

// The CPU: what it did over PLB1 and on its memory path; its software stage (by step, by
// unit of work, its instructions, its L1).
std::string cpu_section(const nlohmann::ordered_json& r) {
    const Shown cpu(r["cpu"], section_statistics("CPU (PPC440)"));
    std::string md = fmt::format(
        "\n## CPU (PPC440)\n\n{} register reads and {} register writes over PLB1; {} cycles of computation; "
        "{} interrupt waits ({} asleep).\n\nMemory over {}: {} read ({} line fills), {} written ({} write-backs); the "
        "CPU stalled {} for its fills, of which {} waiting for the DRAM behind other traffic.\n",
        cpu.count("mmio_reads"), cpu.count("mmio_writes"), cpu.count("cycles_consumed"), cpu.count("irq_waits"),
        ms(cpu.number("irq_wait_s")),
        cpu.text("memory.path") == "mci" ? "the memory controller interface (MCI)" : "PLB1",
        mib(cpu.number("memory.bytes_read")), cpu.count("memory.line_fills"), mib(cpu.number("memory.bytes_written")),
        cpu.count("memory.write_backs"), ms(cpu.number("memory.fill_stall_s")), ms(cpu.number("memory.ddr_wait_s")));
    if (r.contains("workload") && r["workload"].contains("software_stage") &&
        !r["workload"]["software_stage"].is_null())
        md += software_stage_section(r["workload"]["software_stage"]);
    return md;
}

std::string simulation_section(const nlohmann::ordered_json& r) {
    std::string md = "\n## Simulation\n\n| | |\n|---|---:|\n";
    md += fmt::format("| simulated time | {} |\n", ms(r["sim_time_s"]));
    md += fmt::format("| wall time | {} |\n", ms(r["wall_time_s"]));
    md += fmt::format("| real-time factor (simulated / wall) | {:.4g} |\n", r["real_time_factor"].get<double>());
    md += fmt::format("| TLM transactions on the PLBs | {} ({:.3g} per wall second) |\n",
                      r["transactions"].get<uint64_t>(), r["transactions_per_second"].get<double>());
    return md;
}

}  // namespace

// Injected faults: the counts, then each fault and what became of its frame.
std::string faults_section(const nlohmann::ordered_json& f) {
    const auto& d = f["driver"];
    std::string md = fmt::format(
        "\n## Injected faults\n\n{} given, {} struck, {} detected, {} recovered (their pair finished a later frame, or "
        "the "
        "frame itself went on); {} frames lost. The driver's watchdog expired {} times, {} interrupts had nothing to "
        "serve, "
        "{} pair resets.\n\n| fault | given at | struck | frame | detected | recovered | outcome "
        "|\n|---|---|---:|---:|---|---|---|\n",
        f["given"].get<size_t>(), f["injected"].get<size_t>(), f["detected"].get<size_t>(),
        f["recovered"].get<size_t>(), f["tasks_lost"].get<size_t>(), d["watchdog_expiries"].get<uint64_t>(),
        d["spurious_interrupts"].get<uint64_t>(), d["pair_resets"].get<uint64_t>());
    auto yes = [](const nlohmann::ordered_json& j, const char* key) { return j.value(key, false) ? "yes" : "**no**"; };
    for (const auto& x : f["list"]) {
        if (!x["struck"].get<bool>()) {
            md += fmt::format("| {} | {} | **never** | | | | |\n", x["fault"].get<std::string>(),
                              x["origin"].get<std::string>());
            continue;
        }
        md += fmt::format("| {} | {} | {:.3f} ms | {} | {} | {} | {} |\n", x["fault"].get<std::string>(),
                          x["origin"].get<std::string>(), x["at_ms"].get<double>(), x["frame"].get<int64_t>(),
                          yes(x, "detected"), yes(x, "recovered"), x.value("outcome", ""));
    }
    return md;
}

// What the configuration needs of the FPGA, per block, against the device.
std::string resources_section(const nlohmann::ordered_json& f) {
    const auto& cap = f["capacity"];
    const auto& total = f["total"];
    std::string md = fmt::format("\n## FPGA resources ({})\n\n", f["device"].get<std::string>());
    md += f["fits"].get<bool>() ? std::string("The configuration fits the device.\n\n")
                                : fmt::format("**The configuration does not fit the device**: {}.\n\n",
                                              fmt::join(f["over"].get<std::vector<std::string>>(), "; "));
    md += "| block | RAMB36 | DSP48E | LUT | FF | basis |\n|---|---:|---:|---:|---:|---|\n";
    for (const auto& [name, b] : f["blocks"].items())
        md += fmt::format("| {} | {:g} | {:g} | {:g} | {:g} | {} |\n", name, b["ramb36"].get<double>(),
                          b["dsp48e"].get<double>(), b["luts"].get<double>(), b["ffs"].get<double>(),
                          b["basis"].get<std::string>());
    auto of = [&](const char* k) {
        return fmt::format("{:g} of {:g} ({:.0f} %)", total[k].get<double>(), cap[k].get<double>(),
                           100 * total[k].get<double>() / cap[k].get<double>());
    };
    md += fmt::format("| **total** | {} | {} | {} | {} | estimates: docs/resources.md |\n", of("ramb36"), of("dsp48e"),
                      of("luts"), of("ffs"));
    return md;
}

// Watts per block over the run and joules per frame, against the power budget.
std::string power_section(const nlohmann::ordered_json& p) {
    std::string md = fmt::format(
        "\n## Power and energy\n\n**{:.2f} W** over the run, **{:.3f} J per frame**; {} the {:g} W budget "
        "(power.budget_w). Estimates from what the run did: docs/power.md.\n\n"
        "| block | W | basis |\n|---|---:|---|\n",
        p["watts"].get<double>(), p["joules_per_frame"].get<double>(),
        p["within_budget"].get<bool>() ? "within" : "**over**", p["budget_w"].get<double>());
    for (const auto& [name, b] : p["blocks"].items())
        md += fmt::format("| {} | {:.3f} | {} |\n", name, b["watts"].get<double>(), b["basis"].get<std::string>());
    if (p.contains("band")) {
        // The assumptions the cost figures rest on, widest first.
        std::vector<std::pair<double, std::string>> spread;
        for (const auto& e : p["band"]["parameters"]) {
            const double lo = e["low"]["watts"], hi = e["high"]["watts"];
            const double ram_lo = e["low"]["ramb36"], ram_hi = e["high"]["ramb36"];
            spread.push_back(
                {std::abs(hi - lo),
                 fmt::format("`{}` {} .. {}: {:.2f} .. {:.2f} W{}", e["parameter"].get<std::string>(),
                             e["low"]["value"].get<std::string>(), e["high"]["value"].get<std::string>(), lo, hi,
                             ram_lo == ram_hi ? "" : fmt::format(", {:g} .. {:g} RAMB36", ram_lo, ram_hi))});
        }
        std::stable_sort(spread.begin(), spread.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        md += fmt::format(
            "\nOver the assumption band of the cost parameters, one at a time: **{:.2f} to {:.2f} W**. Widest:\n\n",
            p["band"]["watts_range"][0].get<double>(), p["band"]["watts_range"][1].get<double>());
        for (size_t i = 0; i < spread.size() && i < 5; ++i) md += "- " + spread[i].second + "\n";
    }
    return md;
}

namespace {

// Why a run broke: the software's failure, else the first check of the run itself that did
// not hold, with its first cause.
std::string why_broken(const nlohmann::ordered_json& r) {
    if (r.contains("failure")) return r["failure"].get<std::string>();
    for (const auto& c : r["checks"]) {
        if (c["passed"].get<bool>() || c.value("kind", "run") == "goal") continue;
        const std::string detail = c["detail"].get<std::string>();
        const size_t more = detail.find("; ");
        return fmt::format("{} failed: {}{}", c["name"].get<std::string>(), detail.substr(0, more),
                           more == std::string::npos ? "" : " (and more)");
    }
    return "";
}

}  // namespace

// Why the chip could not have been built (it does not fit the device with its placement
// margin, or a clock does not close), or "".
std::string why_unbuildable(const nlohmann::ordered_json& r) {
    std::string why;
    for (const auto& c : r["checks"])
        if (!c["passed"].get<bool>() && (c["name"] == "fits the FPGA" || c["name"] == "closes its clocks"))
            why += (why.empty() ? "" : "; ") + c["detail"].get<std::string>();
    return why;
}

std::string answer_line(const nlohmann::ordered_json& r) {
    if (r.value("broken", false)) return why_broken(r);
    const std::string unbuildable = why_unbuildable(r);
    const std::string first = unbuildable.empty() ? "" : "Not buildable: " + unbuildable + ". ";
    if (r.contains("verdict") && r["verdict"].contains("statement"))
        return first + "Verdict: " + r["verdict"]["statement"].get<std::string>();
    if (!r.contains("throughput_fps")) return first.empty() ? "" : first.substr(0, first.size() - 2);
    return first + frame_rate_answer(r);
}

std::string frame_rate_answer(const nlohmann::ordered_json& r) {
    const RunSummary run = RunSummary::of(r);
    std::string line = fmt::format("{:.2f} frames/s", run.fps);
    if (run.budget_met)
        line += fmt::format(" against a budget of {:.2f}: {}", run.budget_fps, *run.budget_met ? "met" : "MISSED");
    if (!run.limit.empty()) line += fmt::format("; limited by {}", run.limit);
    return line;
}

std::string report_markdown(const nlohmann::ordered_json& r) {
    std::string md = fmt::format("# surfvp run: {}\n\n{}\n\n", r["scenario"]["name"].get<std::string>(),
                                 r["scenario"]["description"].get<std::string>());
    md += headline(r);
    md += fmt::format("**Result: {}**", RunSummary::of(r).result());
    if (r.contains("failure")) md += fmt::format(": {}", r["failure"].get<std::string>());
    md += "\n\n| check | result | detail |\n|---|---|---|\n";
    for (const auto& c : r["checks"])
        md += fmt::format("| {} | {} | {} |\n", c["name"].get<std::string>(), c["passed"].get<bool>() ? "pass" : "FAIL",
                          c["detail"].get<std::string>());
    if (r.contains("verdict")) md += verdict_section(r["verdict"]);
    if (r.contains("correlation")) md += correlation_markdown(r["correlation"]);
    if (r.contains("faults")) md += faults_section(r["faults"]);
    if (r.contains("throughput_fps")) md += frames_section(r);
    md += accelerators_section(r);
    if (r.contains("cpu")) md += cpu_section(r);
    if (r.contains("fpga_resources")) md += resources_section(r["fpga_resources"]);
    if (r.contains("power")) md += power_section(r["power"]);
    const double seconds = r["sim_time_s"].get<double>();
    const double frames = std::max(1.0, r.value("frames_done", 1.0));
    md += fmt::format("\n## Buses and DDR (in total over {} and per frame)\n", ms(seconds));
    for (const auto& [name, bus] : r["buses"].items()) bus_section(md, name, bus, seconds, frames);
    md += memory_section(r["memory"], seconds, frames);
    if (r.contains("workload")) md += workload_section(r["workload"]);
    md += files_section(r["outputs"]);
    md += simulation_section(r);
    md +=
        "\n## Every statistic\n\n<details><summary>As the blocks registered them; report.json holds the same under "
        "each "
        "path.</summary>\n\n" +
        statistics_markdown(r) + "\n</details>\n";
    return md;
}

}  // namespace surfvp
