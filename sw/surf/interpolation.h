#pragma once
// Sub-pixel and sub-scale refinement of a local maximum (paper §II, eqs. 4-5; Brown & Lowe).
#include <optional>

#include "sw/surf/keypoint.h"
#include "sw/surf/local_maxima.h"

namespace surfvp::surf {

// Fits a quadratic to the 3x3x3 neighbourhood (gradient and Hessian by central finite
// differences in sample units of x, y and interval) and moves to its vertex: offset =
// -H^-1 g. Rejected (nullopt) when H is singular or any |offset| > max_offset (the paper's
// rule is 0.5: the true maximum is nearer another sample; OpenCV keeps up to 1, which keeps
// the maxima that fall between two samples: Params::max_offset). Otherwise the keypoint is
//   x = (kx + ox) * step,  y = (ky + oy) * step,
//   L = L(layer) + os * filter_spacing(octave),  scale = 1.2 L / 9,
// response = the sample's determinant. Laplacian and orientation are left at 0.
std::optional<Keypoint> interpolate_maximum(const ResponseStack& stack, const LocalMaximum& m, float max_offset);

}  // namespace surfvp::surf
