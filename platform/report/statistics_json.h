#pragma once
// The one generic path from the statistics registry (models/common/statistics.h) to the
// reports: the figures as report.json's tree (a path's levels as nested objects, numbered
// instances as arrays), their kinds, units and meanings by path (report.json's
// "statistics"), and every figure as a Markdown table for report.md.
#include <nlohmann/json.hpp>
#include <string>

#include "models/common/statistics.h"

namespace surfvp {

nlohmann::ordered_json statistics_tree(const Statistics& statistics, double elapsed_s);
nlohmann::ordered_json statistics_legend(const Statistics& statistics);

// Every figure the legend lists, read from `report` by its path, with its unit and meaning.
std::string statistics_markdown(const nlohmann::ordered_json& report);

}  // namespace surfvp
