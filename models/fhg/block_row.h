#pragma once
// One block row as the FHG produces it (the model and direct mode alike): its determinants
// stored as the writer sends them to memory (DET_BYTES each, big-endian, fhg_regs.h) and the
// candidates LocMaxFinder marks in it. Plain C++, safe on any thread (the scratch is the
// thread's own).
#include <cstdint>
#include <vector>

#include "hessian_core.h"
#include "local_max_finder.h"

namespace surfvp::fhg {

std::vector<Candidate> block_row(const HessianCore& core, const IntegralView& lines, int by, int32_t threshold,
                                 uint32_t det_bytes, uint8_t* row);
// The same from a block row's records given whole (another datapath's: fhg.model=rtl).
std::vector<Candidate> block_row(const std::vector<int32_t>& records, int by, int32_t threshold, uint32_t det_bytes,
                                 uint8_t* row);

}  // namespace surfvp::fhg
