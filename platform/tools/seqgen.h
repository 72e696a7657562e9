#pragma once
// `surfvp seqgen`: the FHG's generated control sequence and what it implies, without a run.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/fhg/fhg.h"

namespace surfvp {

struct SeqgenOptions {
    std::string scenario;  // optional: parameters start from this scenario
    std::vector<std::string> sets;
    unsigned width = 1024, height = 768;
};

// Prints one JSON object on stdout; throws ConfigError for bad input.
int seqgen_command(const SeqgenOptions& options);

// The machine the sequence is scheduled on and the three figures: the basic script (with
// the spread of its passes), the improved one, and the lower bound with what sets it; and
// the cycles per block the chip runs with. Throws std::invalid_argument for an impossible
// configuration.
nlohmann::ordered_json schedule_figures(const Fhg::Params& params);

}  // namespace surfvp
