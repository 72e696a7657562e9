#pragma once
// `surfvp compare A B [...]` and `surfvp run --compare-to DIR` (docs/compare.md): runs side by
// side. Each side is a run folder (its report.json and config.yaml) or a sweep's point
// (SWEEP_DIR@N, from its results.json). The first side is the reference: the parameters that
// differ, every figure with its delta and % against the reference, and which budgets each
// meets (frame rate, power, the FPGA), as Markdown and JSON.
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

namespace surfvp {

// Throws ConfigError naming a side that is not a run folder or a sweep point.
nlohmann::ordered_json compare_runs(const std::vector<std::string>& sides);
void check_side(const std::string& side);  // the same check alone, before a run
std::string compare_markdown(const nlohmann::ordered_json& comparison);

struct CompareOptions {
    std::vector<std::string> sides;
    std::string json;  // also write the comparison here ("" : not)
};
int compare_command(const CompareOptions& options);

// `run --compare-to`: the comparison of the run in `staging` (published as `published`)
// against `reference`, as compare.md and compare.json in `staging`.
void write_comparison(const std::string& reference, const std::string& staging, const std::string& published);

}  // namespace surfvp
