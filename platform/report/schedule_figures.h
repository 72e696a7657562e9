#pragma once
// The FHG's control sequence in figures, as report.json and `surfvp seqgen` give them.
#include <nlohmann/json.hpp>

#include "models/fhg/fhg.h"

namespace surfvp {

// The machine the sequence is scheduled on and the three figures: the basic script (with
// the spread of its passes), the improved one, and the lower bound with what sets it; and
// the cycles per block the chip runs with. Throws std::invalid_argument for an impossible
// configuration.
nlohmann::ordered_json schedule_figures(const Fhg::Params& params);

}  // namespace surfvp
