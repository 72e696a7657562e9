#pragma once
// A sweep file (docs/sweeps.md): a base scenario, parameters fixed for every point, and axes
// whose values are combined into points (cartesian, or zipped in step).
//
//   name: fhg_clock
//   scenario: budget_1024x768          # a shipped name or a path (relative to this file)
//   set: {surf.frames: 5}              # every point
//   axes:
//     fhg.clock: {from: 50 MHz, to: 150 MHz, step: 25 MHz}
//     fhg.read_buses: [2, 4, 6]
//   combine: cartesian                 # or zip
//
// Every value is checked against its parameter when the file is loaded, so a bad axis is
// reported at its line before any point runs.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <nlohmann/json.hpp>

#include "platform/scenario/config.h"

namespace surfvp {

struct SweepAxis {
    std::string key;
    std::vector<std::string> values;  // as a parameter takes them ("75 MHz", "4")
    std::string origin;               // FILE:LINE
};

struct SweepPoint {
    size_t index = 0;                                         // in the plan's order, from 0
    std::vector<std::pair<std::string, std::string>> values;  // one per axis
    std::string id;                                           // "fhg.clock=75 MHz, fhg.read_buses=4"
};

struct SweepPlan {
    std::string file, name, description;
    std::string scenario;           // the base scenario's file
    std::vector<std::string> sets;  // KEY=VALUE for every point
    std::vector<SweepAxis> axes;
    bool zip = false;
    std::vector<SweepPoint> points;
    // What the points' results rest on, whatever folder the sweep is run from and however its
    // files are spelt: surfvp's version, the base scenario's text, the fixed sets and the axes
    // (keys, values, how they combine). A path's value is its file's one absolute spelling.
    nlohmann::ordered_json identity;
    std::string fingerprint;  // identity as text: sweep.db's, to compare

    // The point's configuration: the base scenario with the fixed sets and its values.
    Config config(const SweepPoint& point) const;
};

// The most points a sweep may have: more are refused when the file is loaded, before any
// point is made, naming each axis and its number of values.
constexpr size_t kMaxSweepPoints = 100000;

// Throws ConfigError naming the file and line.
SweepPlan load_sweep(const std::string& path);

// What differs between the sweep of fingerprint `before` and `now`, one phrase each: "base
// scenario changed", "set changed (surf.frames: 3, now 5)", "axis fhg.clock: values changed
// (...)", "axes added: ...", "combine changed (cartesian, now zip)". Empty when they are equal.
std::vector<std::string> sweep_changes(const std::string& before, const std::string& now);

// A point's id from its values in the axes' order: "fhg.clock=75 MHz, fhg.read_buses=4", or
// "(base)" for a sweep without axes.
std::string point_id(const std::vector<std::pair<std::string, std::string>>& values);

// The points `axes` make, crossed (the last axis varies fastest) or zipped, each with its id.
// Throws ConfigError (with `where`) for zipped axes of different lengths or more than
// kMaxSweepPoints points, before any point is made.
std::vector<SweepPoint> combine_axes(const std::vector<SweepAxis>& axes, bool zip, const std::string& where);

// A number and its unit: "25 MHz" -> {25, "MHz"}, "4" -> {4, ""}; nothing for a word, nor
// for a number beyond a double's range ("1e400 MHz") unless `any_magnitude`.
std::optional<std::pair<double, std::string>> split_quantity(const std::string& text, bool any_magnitude = false);

// "50 MHz", "150 MHz", "25 MHz" -> 50 MHz, 75 MHz, ..., 150 MHz (the unit of `from`; `to` is
// included when the steps land on it). Throws ConfigError (with `where`) for a step that is
// not positive, units that differ, or more than `limit` values.
std::vector<std::string> expand_range(const std::string& from, const std::string& to, const std::string& step,
                                      const std::string& where, size_t limit = 100000);

}  // namespace surfvp
