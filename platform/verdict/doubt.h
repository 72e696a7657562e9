#pragma once
// The doubt of the verdict, jointly (docs/architecture.md#principles, 7): the unknowns about the chip (banded
// parameters of role `unknown`) sampled together over their bands, each point re-simulated, so
// that an assumption that does not matter at the defaults but does once another moves shows up.
// - The design is a Latin hypercube: each unknown's range (or its low, default and high, for a
//   choice or a width) is cut into as many strata as points, each stratum used once; a fixed
//   seed, so the same scenario samples the same points.
// - The frame rate's distribution is the points' own (5th, 50th, 95th percentile; the share
//   that meets the budget), each point's rate being the run's plus its effect against the
//   reference, as for the one-at-a-time band.
// - The variance-based sensitivity of each unknown (first-order and total Sobol indices) is
//   computed on a surrogate fitted to the points: per resource, the logarithm of the frame rate
//   it alone would allow, linear in the unknowns; the surrogate's rate is the least of those,
//   scaled to the points. Its fit (R^2 against the points' rates) is reported with the indices.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "models/common/parameter.h"
#include "platform/scenario/config.h"

namespace surfvp {

struct Unknown {
    const ParamSpec* spec;
    std::vector<std::string> values;  // a choice or a width: the distinct values of low, default, high
    double low = 0, high = 0;         // otherwise its range, in the kind's base unit
    bool continuous() const { return values.empty(); }
};

// The unknowns among `banded` whose band moves a value (low or high differs from the default).
std::vector<Unknown> unknowns_of(const std::vector<const ParamSpec*>& banded, const Config& config);

struct JointDesign {
    std::vector<std::vector<double>> unit;  // per point, per unknown: its coordinate in [0, 1)
    std::vector<std::vector<std::pair<std::string, std::string>>> sets;  // per point: what to set
};
JointDesign joint_design(const std::vector<Unknown>& unknowns, size_t points, uint32_t seed);

// `results[i]` is point i's summary (fps, alone_fps per resource), or {"error": ...}.
nlohmann::ordered_json doubt_json(const std::vector<Unknown>& unknowns, const JointDesign& design,
                                  const std::vector<nlohmann::ordered_json>& results, double run_fps,
                                  double reference_fps, double budget, unsigned frames);

}  // namespace surfvp
