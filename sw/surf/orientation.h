#pragma once
// Orientation assignment (paper §II, step 3; Bay et al. 2008 §4.1).
#include "sw/surf/integral_image.h"
#include "sw/surf/keypoint.h"

namespace surfvp::surf {

// Dominant direction of the interest point at (x, y) with scale s, radians in [0, 2 pi),
// measured from +x towards +y in image axes (x right, y down): atan2(sum dy, sum dx).
//
// Haar wavelets of size 4s are sampled every s inside a circle of radius 6s (the 109 grid
// points with i^2 + j^2 < 36), weighted by a Gaussian of sigma 2.5s centred on the point. A
// window of pi/3 slides around the circle in steps of pi/18; the window whose summed
// (dx, dy) is longest gives the direction. Because both the width and the step are multiples
// of pi/18, responses are summed into 36 bins of pi/18 first and a window is 6 adjacent bins,
// which is exactly the sliding-window sum.
float orientation(const IntegralView& ii, float x, float y, float scale);

}  // namespace surfvp::surf
