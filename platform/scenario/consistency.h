#pragma once
// What the parameter table cannot say on its own: parameters that contradict each other, and
// parameters that are given but cannot take effect in this scenario. Both are decided before
// anything is built, so that `surfvp validate` reports them at the parameter's origin (file
// and line, or --set) and a run finds nothing of the kind after simulating.
#include <string>
#include <vector>

#include "platform/scenario/config.h"

namespace surfvp {

// Throws ConfigError at the first combination that is clearly a mistake: half an image
// size, an evaluation or a fault that needs frames the scenario does not have, a PLB width
// the bus does not have, too few interrupt inputs for the accelerator pairs.
void check_consistency(const Config& config);

// A parameter given (in the file or by --set), at a value other than its default, that
// nothing in this scenario reads.
struct Ineffective {
    std::string key;
    std::string reason;  // why it has no effect, naming the parameter that decides it
};
std::vector<Ineffective> ineffective_parameters(const Config& config);

}  // namespace surfvp
