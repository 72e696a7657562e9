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

// The power estimate's prices (power.*): watts of what is always on, and energy per event.
struct PowerPrices {
    double budget_w = 0, static_w = 0, ddr_background_w = 0, infrastructure_w = 0;
    double ppc440_mw_per_mhz = 0, logic_pj_per_cell_cycle = 0, bram_pj_per_access = 0, dsp_pj_per_product = 0;
    double bus_pj_per_bit = 0, bus_pj_per_burst = 0, ddr_pj_per_bit = 0;

    static const ParamTable<PowerPrices>& parameter_table();
};
PowerPrices power_prices(const ParamValues& values);

// `report`: the run's report.json as built so far (sim_time_s, frames_done, cpu, iig, fhg,
// buses, memory, time_per_frame).
nlohmann::ordered_json power_estimate(const Config& config, const nlohmann::ordered_json& report,
                                      const FpgaResources& resources);

// The cost figures' own assumption band: each banded fpga.* and power.* parameter at its low
// and at its high, one at a time, re-evaluated on the same run (no re-simulation: they move no
// simulated figure): watts, RAMB36 and LUTs at each end, and the whole range.
nlohmann::ordered_json cost_band(const Config& config, const nlohmann::ordered_json& report);

}  // namespace surfvp
