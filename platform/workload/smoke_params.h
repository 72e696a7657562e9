#pragma once
// The smoke software's declarations (smoke.*), bound to the SmokeConfig fields they set.
#include "models/common/parameter.h"
#include "sw/smoke/smoke_software.h"

namespace surfvp {

const ParamTable<sw::SmokeConfig>& smoke_parameter_table();

}  // namespace surfvp
