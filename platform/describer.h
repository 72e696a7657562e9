#pragma once
// The software stage libSSA2 hands candidates to, built from the configuration.
#include <memory>

#include "config.h"
#include "sw/libssa2/libssa2.h"

namespace surfvp {

std::unique_ptr<sw::ssa2::Describer> make_describer(const Config& config, float threshold);

}  // namespace surfvp
