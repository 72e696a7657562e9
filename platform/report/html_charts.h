#pragma once
// report.html's charts, each an inline SVG that scales with the page (a viewBox, width 100 %):
// axes scaled to the data with round-number ticks (chart_ticks.h), every colour named in a
// legend in view (a tooltip only repeats what is drawn), readable in black and white print.
// Each chart carries the figures it draws as data-* attributes, which the tests read.
#include <nlohmann/json.hpp>
#include <string>

namespace surfvp {

// The first frames across the chip: each pair's IIG and FHG, PLB2 (their DMA), the CPU.
std::string gantt_chart(const nlohmann::ordered_json& report);
// Each resource's frame period as busy, each wait cause and idle.
std::string resource_chart(const nlohmann::ordered_json& time_per_frame);
// Bus and DDR busy shares over the run.
std::string bus_chart(const nlohmann::ordered_json& report);
// The FHG's line and maxima FIFO levels over the run.
std::string fifo_charts(const nlohmann::ordered_json& report);
// The joint band's frames/s: its spread (min, 5th to 95th percentile, median, max) against
// the budget and the rate at the defaults.
std::string distribution_chart(const nlohmann::ordered_json& verdict);
// The FPGA's resources as shares of the device, and the watts against the power budget.
std::string cost_chart(const nlohmann::ordered_json& report);

}  // namespace surfvp
