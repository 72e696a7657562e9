#pragma once
// What a sweep gives: each point's figures taken from its report, the Pareto front, and the
// results as results.csv, results.json and SVG plots (frames/s against each axis).
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "platform/sweep/sweep_store.h"

namespace surfvp {

// The objectives the front is taken on: frames/s and feature quality when measured (higher is
// better), block RAM, DSP slices and watts when the rows carry them (lower is better).
struct Objective {
    std::string figure;
    bool higher_is_better;
};
std::vector<Objective> pareto_objectives(const std::vector<SweepRow>& rows);
// Per row: whether no other row that ran is at least as good on every objective and better
// on one (figures within 0.1 % of each other count as equal).
std::vector<bool> pareto_front(const std::vector<SweepRow>& rows, const std::vector<Objective>& objectives);

// results.csv, results.json and plot_<axis>.svg (one per axis) into `dir`; `axes` in the
// sweep's order; `notes` go into results.json as they are (a partial merge's missing shards).
// Returns the files written.
std::vector<std::string> write_sweep_results(const std::string& dir, const std::string& name,
                                             const std::vector<std::string>& axes, const std::vector<SweepRow>& rows,
                                             const nlohmann::ordered_json& notes = nlohmann::ordered_json::object());

}  // namespace surfvp
