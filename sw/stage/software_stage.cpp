#include "sw/stage/software_stage_impl.h"

namespace surfvp::sw {

template class BasicSoftwareStage<CostCounter>;

}  // namespace surfvp::sw
