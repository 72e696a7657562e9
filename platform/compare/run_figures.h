#pragma once
// Every numeric figure of a run's report.json by its path ("fhg.busy_fraction"), for compare:
// what is not a figure of the chip (wall clock, the legend, per-frame rows, time series, the
// workload's own section, the verdict's) left out. The report is read back, so untrusted:
// any JSON value is accepted (what is not an object or a number is no figure).
#include <nlohmann/json.hpp>

namespace surfvp {

nlohmann::ordered_json all_figures(const nlohmann::ordered_json& report);

}  // namespace surfvp
