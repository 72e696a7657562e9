#pragma once
// JSON pieces shared by `surfvp eval` and `surfvp eval-seq` (key order is part of the output).
#include <nlohmann/json.hpp>

#include "sw/eval/distinguishability.h"

namespace surfvp::quality {

inline const char* status_name(eval::DistinguishabilityStatus status) {
    switch (status) {
        case eval::DistinguishabilityStatus::ok:
            return "ok";
        case eval::DistinguishabilityStatus::no_candidates:
            return "no_candidates";
        case eval::DistinguishabilityStatus::too_few_candidates:
            return "too_few_candidates";
        case eval::DistinguishabilityStatus::no_fundamental:
            return "no_fundamental";
    }
    return "unknown";
}

// The ratio test's settings; a search radius of null means unlimited.
inline nlohmann::ordered_json matching_json(const eval::RatioTestOptions& matching) {
    nlohmann::ordered_json j;
    j["search_radius"] = matching.search_radius ? nlohmann::ordered_json(*matching.search_radius) : nullptr;
    j["same_laplacian"] = matching.same_laplacian;
    j["ratio"] = matching.ratio;
    return j;
}

}  // namespace surfvp::quality
