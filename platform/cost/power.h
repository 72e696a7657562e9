#pragma once
// Power and energy of a run (docs/power.md): an activity-based estimate per block from what the
// run did (each block's computing time, the bytes and bursts on each bus, the DDR's bytes, the
// determinants) and the power.* parameters (static power, energy per logic cell and cycle, per
// block-RAM access, per multiplication, per bit moved, per burst, PPC440 mW/MHz, DDR2 energy
// per bit), giving watts and joules per frame, checked against the paper's "less than 10 W".
#include <nlohmann/json.hpp>

#include "platform/cost/fpga_resources.h"
#include "platform/scenario/config.h"

namespace surfvp {

// `report`: the run's report.json as built so far (sim_time_s, frames_done, cpu, iig, fhg,
// buses, memory, time_per_frame).
nlohmann::ordered_json power_estimate(const Config& config, const nlohmann::ordered_json& report,
                                      const FpgaResources& resources);

}  // namespace surfvp
