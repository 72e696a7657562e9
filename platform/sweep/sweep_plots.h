#pragma once
// A sweep's SVG plots: frames/s against one axis, and the Pareto front (frames/s against a
// cost), with the budget dashed and the points on the front filled.
#include <string>
#include <vector>

#include "platform/sweep/sweep_store.h"

namespace surfvp {

// A line through the points that share every other axis's value, labelled with those values.
std::string axis_plot(const std::string& name, const std::string& axis, const std::vector<std::string>& axes,
                      const std::vector<SweepRow>& rows, const std::vector<bool>& front);
// Frames/s against the figure `cost` (watts, bram36), every point (filled: on the front of
// all objectives) and a staircase of the most frames/s for each cost.
std::string front_plot(const std::string& name, const std::string& cost, const std::vector<SweepRow>& rows,
                       const std::vector<bool>& front);

}  // namespace surfvp
