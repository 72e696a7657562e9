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
    double cycles = 0;              // per unit, the table's defaults, every access an L1 hit
    std::vector<double> low, high;  // per unit with knob k (pipeline_knobs()) at its low / high probe
    double instructions = 0;
    std::array<double, kInsnClasses> mix{};
    double libm_calls = 0, libm_instructions = 0;
};
using UnitTable = std::array<UnitCalibration, kUnits>;

// The prices under one FPU precision (fpu.precision): its latency column is the defaults.
struct PrecisionTable {
    std::vector<double> defaults;         // each knob's value when measured
    std::vector<double> low_at, high_at;  // each knob's probe values (the default itself: no probe)
    std::array<UnitTable, 2> haar;        // [exact, rounded]
};

struct Calibration {
    nlohmann::ordered_json provenance;        // toolchain, flags, ISS, input
    std::array<PrecisionTable, 2> precision;  // [single, double]
    // Per calibration run: the stream's and the table's cycles per keypoint by step, and the
    // units per keypoint (tests/stage holds the table to them).
    nlohmann::ordered_json agreement = nlohmann::ordered_json::array();
    // Points where several knobs move at once: the stream re-timed there against the prices
    // (tests/stage holds unit_prices() to them).
    nlohmann::ordered_json checks = nlohmann::ordered_json::array();
    // Per Haar mode, a few whole candidates of the stream (the first keypoints of the first
    // fitting run): re-timed under the parameters a run asks for, they scale the prices.
    std::array<StreamSample, 2> sample;
    // The same from the M-SURF run: they scale the msurf unit's price (its mix of loads,
    // converts and FPU work is not Bay's descriptor's). Empty: M-SURF not priced.
    std::array<StreamSample, 2> msurf_sample;
};

const Calibration& recorded_calibration();                           // calibration.json, embedded at build time
Calibration calibration_from_json(const nlohmann::ordered_json& j);  // throws std::runtime_error
nlohmann::ordered_json calibration_to_json(const Calibration& c);

// CPU cycles per unit for these pipeline parameters, from the table of their precision: the
// recorded cycles at its defaults, scaled step by step by the sample re-timed (the sample's
// cycles in that step under `params` over its cycles under the defaults); the msurf unit by
// the M-SURF run's sample. The knobs interact
// (an FPU latency counts times the clock ratio, an issue occupancy only where the stream
// waits for it), so no sum over one-knob changes prices a point where several move.
std::array<double, kUnits> unit_prices(surf::HaarMode haar, const PipelineParams& params,
                                       const Calibration& calibration = recorded_calibration());
// The same, extrapolated from the one-knob probes, knob by knob and linearly (what the prices
// were before the sample; the calibration reports how far it is from the stream).
std::array<double, kUnits> linear_unit_prices(surf::HaarMode haar, const PipelineParams& params,
                                              const Calibration& calibration = recorded_calibration());
// The sample's cycles per step under each parameter set.
std::vector<std::array<double, kSteps>> sample_cycles(const StreamSample& sample,
                                                      const std::vector<PipelineParams>& sets);

// The cost model's parameters with the recorded prices for this Haar mode and pipeline; the
// cache and miss cost as CostParams' defaults.
inline CostParams calibrated_cost_params(surf::HaarMode haar, const PipelineParams& pipeline = {}) {
    CostParams p;
    p.unit_cycles = unit_prices(haar, pipeline);
    return p;
}

// A knob's probe values around `base` (its low and high, or a step beyond the default when it
// sits at one end of its range; a choice's other value); equal to the base: not probed.
std::pair<double, double> probe_values(const PipelineKnob& knob, double base);

// The parameter sets a calibration prices the stream at, around `base`: the base, then each
// knob's low and high probe in pipeline_knobs() order (fpu.precision is not probed: each
// precision has its own table).
std::vector<PipelineParams> calibration_parameter_sets(const PipelineParams& base);

// Fits one Haar mode's table: each step's stream (cycles under the parameter sets from
// `first_set` on, in calibration_parameter_sets() order; instructions, mix) as a sum over its
// units, by least squares over the candidates. `units[c]` is what the native stage counted
// for candidate c.
UnitTable fit_units(const std::vector<CandidateStream>& stream, const std::vector<std::array<uint64_t, kUnits>>& units,
                    size_t first_set = 0, bool probed = true);

}  // namespace surfvp::sw
