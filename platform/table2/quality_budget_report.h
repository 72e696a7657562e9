#pragma once
// The quality budget's analysis and pages (docs/quality_budget.md), from its report.json:
// each setting's scores, the Pareto fronts of quality against frames/s, the best setting the
// budget affords and its gap to the best float SURF; report.md, results.csv, frontier.svg.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace surfvp {

// Frames/s closer than this are the same frame rate on the fronts: the interrupt timing moves a
// run's rate by a few thousandths when the software's work changes, the FHG's period not at all.
constexpr double kFrontFpsResolution = 0.01;

// Whether a point's budget run and chip runs all ran and none broke: its row is a measurement.
bool setting_ran(const nlohmann::ordered_json& point);

// Adds to each point its distinguishability (mean of the four rows on consecutive frames, RANSAC
// F, over the sequences chosen on), pair precision, "affordable" (the CPU alone sustains the
// budget), "meets_budget" and its place on the two fronts; then "best_affordable" (an index
// into points, or null) and the gaps to the best float of it and of the paper's software.
void analyse_quality_budget(nlohmann::ordered_json& report);

std::string quality_budget_markdown(const nlohmann::ordered_json& report);
std::string quality_budget_csv(const nlohmann::ordered_json& report);
std::string quality_budget_svg(const nlohmann::ordered_json& report);
// The terminal's last line: the best affordable setting and its quality, where the report is.
std::string quality_budget_summary(const nlohmann::ordered_json& report, const std::filesystem::path& md);

}  // namespace surfvp
