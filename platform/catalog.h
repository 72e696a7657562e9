#pragma once
// The chip's catalog of parameters: every key a scenario may set, gathered from the
// declarations beside the code that reads each (a block's in models/<block>/*_params.cpp, the
// run's in scenario/run_settings.cpp, the workload's in workload/, the costs' in
// cost/cost_params.cpp), in the order docs/parameters.md lists them, with the assumption
// bands. scenario/parameters.h declares parameter_table(); this unit, the chip's top, defines
// it, so the configuration layer never includes what it configures.
//
// The verdict's own settings are declared here too: the chip's configuration must know every
// key a scenario may give, and the chip never includes the application, which reads them
// through VerdictSettings.
#include <cstdint>

#include "models/common/parameter.h"

namespace surfvp {

struct VerdictSettings {
    bool break_even = false;  // verdict.break_even
    bool band = false;        // verdict.band
    bool software = false;    // verdict.software
    uint64_t frames = 2;      // verdict.frames: each re-simulation's frames
    uint64_t samples = 0;     // verdict.samples: the joint sample's points
    unsigned jobs = 0;        // verdict.jobs (0: one per core)

    static const ParamTable<VerdictSettings>& parameter_table();
};
VerdictSettings verdict_settings(const ParamValues& values);

// The frames each of the verdict's re-simulations runs: verdict.frames, but enough for every
// pair to reach its steady state (a frame rate needs soc.accelerators + 1) and no more than
// the scenario has (surf.frames).
unsigned resimulation_frames(const ParamValues& values);

}  // namespace surfvp
