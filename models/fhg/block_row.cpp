#include "block_row.h"

#include "fhg_regs.h"

namespace surfvp::fhg {

std::vector<Candidate> block_row(const HessianCore& core, const IntegralView& lines, int by, int32_t threshold,
                                 uint32_t det_bytes, uint8_t* row) {
    const int blocks = (lines.width + 1) / 2;
    thread_local std::vector<int32_t> records;
    records.resize(size_t(blocks) * kDeterminantsPerBlock);
    core.block_row(lines, by, records.data());
    fhg_regs::store_dets(row, records.data(), records.size(), det_bytes);
    std::vector<Candidate> found;
    LocalMaxFinder(threshold).block_row(records.data(), blocks, by, found);
    return found;
}

}  // namespace surfvp::fhg
