#pragma once
// The statistics each section of report.md shows, by their registry paths
// (models/common/statistics.h): a section reads a statistic only through its list, and
// tests/platform/report/section_statistics_test.cpp holds every listed path against the
// registry of a run, so a statistic renamed in a model fails a test, not the report.
#include <string>
#include <string_view>
#include <utility>
#include <vector>
#include <nlohmann/json.hpp>

namespace surfvp {

// One section's statistics: under the registry node `node` ("buses.*"), each `leaf`
// ("read.bytes", "masters.*.bursts"). A '*' stands for any one name or instance (a bus, a
// master, a port).
struct SectionStatistics {
    std::string section;  // report.md's heading
    std::string node;
    std::vector<std::string> leaves;
};
const std::vector<SectionStatistics>& report_statistics();
const SectionStatistics& section_statistics(std::string_view section);

// A section's view of its node of report.json. Reading a leaf the section does not list is a
// programming error (std::logic_error naming both); a listed leaf the report lacks is null.
class Shown {
public:
    Shown(const nlohmann::ordered_json& node, const SectionStatistics& section, std::string prefix = "")
        : node_(node), section_(section), prefix_(std::move(prefix)) {}

    const nlohmann::ordered_json& operator[](std::string_view leaf) const;
    double number(std::string_view leaf) const;
    uint64_t count(std::string_view leaf) const;
    std::string text(std::string_view leaf) const;
    // The instances under `level` ("masters"): each by name, as a view of its leaves.
    std::vector<std::pair<std::string, Shown>> each(std::string_view level) const;

private:
    const nlohmann::ordered_json& node_;
    const SectionStatistics& section_;
    std::string prefix_;  // "masters.*." within an instance
};

}  // namespace surfvp
