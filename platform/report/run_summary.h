#pragma once
// What a run comes to, read once from its report.json: the frame rate against the budget, the
// limit and its cause, each resource's busy share and what it alone would allow, the CPU's
// time, the costs and the feature quality when the run has them, and whether it passed. The
// verdict's re-simulations, a sweep's rows, compare's main table and the terminal's last line
// (of a timed run or of direct mode) all take their figures from this one struct. The report
// may be another version's or a damaged one (compare and sweep read run folders back): every
// lookup is checked, and a figure the report lacks is 0, "" or absent.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <nlohmann/json.hpp>

namespace surfvp {

struct RunSummary {
    bool passed = false;
    bool broken = false;  // the software stalled or failed, a frame was lost, a fault not recovered
    std::string failure;  // why the software did not finish, or ""
    double fps = 0;       // steady-state frames/s (0: none, as in direct mode)
    double budget_fps = 0;
    std::optional<bool> budget_met;  // absent without a budget
    double latency_ms = 0;
    std::string limit, limit_cause;  // the busiest resource and why ("": none)
    double keypoints_per_frame = 0;
    double sim_time_s = 0, wall_time_s = 0;

    struct Resource {
        std::string name;
        double busy_share = 0;
        std::optional<double> alone_fps;  // what it alone would allow (absent: it sets no rate)
    };
    std::vector<Resource> resources;  // in the report's order

    struct Cpu {
        double ms_per_frame = 0, alone_fps = 0, fill_stall_ms = 0;
    };
    std::optional<Cpu> cpu;  // absent without a CPU row (direct mode)

    // The costs and the feature quality the report has, by figure name in the sweep's columns
    // (bram36, dsp48e, luts, fits, watts, joules_per_frame, within_power_budget, repeatability,
    // precision, distinguishability): only those present.
    std::vector<std::pair<std::string, nlohmann::ordered_json>> extras;

    static RunSummary of(const nlohmann::ordered_json& report);

    // The result in one word, as the exit code tells it: "passed" (0), "FAILED" (1: a goal
    // missed), "BROKEN" (6: the run itself broke).
    const char* result() const { return broken ? "BROKEN" : passed ? "passed" : "FAILED"; }

    // A re-simulated point as the verdict takes it (fps, passed, limit, keypoints, the CPU's
    // time, what each resource alone allows).
    nlohmann::ordered_json point() const;
    // A sweep's row and compare's main figures (sweep.md's columns).
    nlohmann::ordered_json figures() const;
    // The unit of one of figures() for format_figure ("frames/s", "ms", "share", "W"; "" for a
    // ratio, a count without a unit, text or a flag).
    static std::string unit_of(const std::string& figure);
};

}  // namespace surfvp
