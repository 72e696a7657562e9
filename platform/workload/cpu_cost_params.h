#pragma once
// The declarations of the software stage's cost model: the L1 data cache's (cpu.dcache_*; its
// line is cpu.cache_line, the CPU's) and the PPC440 pipeline's knobs
// (sw/cpu_cost/ppc440_pipeline.h). The describer reads them (describer.h: pipeline_params).
#include <vector>

#include "models/common/parameter.h"
#include "sw/cpu_cost/cache_model.h"

namespace surfvp {

const ParamTable<sw::CacheParams>& cache_parameter_table();
std::vector<ParamSpec> pipeline_parameters();

}  // namespace surfvp
