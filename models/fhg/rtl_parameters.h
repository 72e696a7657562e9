#pragma once
// The Verilog reference's parameters (models/fhg/rtl), generated from the declarations the
// model itself uses: HessianCore's Precision and its constants (K_L, W), the block record's
// determinants (filter_geometry.h) and the sequence memory's layout (sequence_memory.h).
// Nothing in the RTL is a copied number. Plain C++.
#include <cstddef>
#include <string>

#include "hessian_core.h"
#include "sequence_generator.h"

namespace surfvp::fhg {

// The RTL's sequence memory holds this many words (sequence_memory.v: one RAMB36 deep at its
// widest, a 9-bit address).
constexpr size_t kRtlSequenceDepth = 512;

// The widths of the RTL's constants, unsigned: the largest K_L's (K_BITS) and W's (W_BITS).
// HessianCalc multiplies by them as signed operands, a bit wider (the resource model's DSP48E).
struct ConstantWidths {
    unsigned k_bits = 0, w_bits = 0;
};
ConstantWidths constant_widths(const HessianCore& core);

// `fhg_params.vh`: localparams and constant functions to `include inside a module. Throws
// std::invalid_argument for a machine the RTL does not build (x3_cycles other than 1 or 3).
// `line_words` is the longest line the line FIFO holds (fhg.max_width).
std::string rtl_parameters(const Precision& precision, const SequenceParams& sequence, unsigned line_words);

}  // namespace surfvp::fhg
