#pragma once
// The native cost model's prices, measured: for each unit of work (work_units.h) and each Haar
// mode, what the software stage's PPC440 instruction stream costs (cycles through the pipeline
// model, instructions by class, libm calls), fitted per unit over every candidate of a
// calibration run, at the default pipeline parameters and with each knob at its two probe
// values. `surfvp calibrate` measures it and writes calibration.json; the build embeds that
// file (the recorded table), and unit_prices() prices any parameter set from it. Plain C++.
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sw/cpu_cost/cost_model.h"
#include "sw/cpu_cost/instruction_trace.h"
#include "sw/cpu_cost/ppc440_pipeline.h"
#include "sw/cpu_cost/work_units.h"
#include "sw/surf/params.h"

namespace surfvp::sw {

struct UnitCalibration {
    double cycles = 0;              // per unit, default parameters, every access an L1 hit
    std::vector<double> low, high;  // per unit with knob k (pipeline_knobs()) at its low / high
    double instructions = 0;
    std::array<double, kInsnClasses> mix{};
    double libm_calls = 0, libm_instructions = 0;
};
using UnitTable = std::array<UnitCalibration, kUnits>;

struct Calibration {
    nlohmann::ordered_json provenance;  // toolchain, flags, ISS, input
    std::vector<double> defaults;       // each knob's value when measured
    std::array<UnitTable, 2> haar;      // [exact, rounded]
    // Per calibration run: the stream's and the table's cycles per keypoint by step, and the
    // units per keypoint (tests/stage holds the table to them).
    nlohmann::ordered_json agreement = nlohmann::ordered_json::array();
};

const Calibration& recorded_calibration();  // calibration.json, embedded at build time
Calibration calibration_from_json(const nlohmann::ordered_json& j);  // throws std::runtime_error
nlohmann::ordered_json calibration_to_json(const Calibration& c);

// CPU cycles per unit for these pipeline parameters: the recorded cycles plus, for each knob
// away from its recorded value, the change its probes measured, linear between (and beyond)
// the probes, knob by knob.
std::array<double, kUnits> unit_prices(surf::HaarMode haar, const PipelineParams& params,
                                       const Calibration& calibration = recorded_calibration());

// The cost model's parameters with the recorded prices for this Haar mode and pipeline; the
// cache and miss cost as CostParams' defaults.
inline CostParams calibrated_cost_params(surf::HaarMode haar, const PipelineParams& pipeline = {}) {
    CostParams p;
    p.unit_cycles = unit_prices(haar, pipeline);
    return p;
}

// The parameter sets a calibration prices the stream at: the defaults, then each knob's low
// and high in pipeline_knobs() order.
std::vector<PipelineParams> calibration_parameter_sets();

// Fits one Haar mode's table: each step's stream (cycles under every parameter set,
// instructions, mix) as a sum over its units, by least squares over the candidates.
// `units[c]` is what the native stage counted for candidate c.
UnitTable fit_units(const std::vector<CandidateStream>& stream, const std::vector<std::array<uint64_t, kUnits>>& units);

}  // namespace surfvp::sw
