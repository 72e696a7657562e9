#pragma once
// SURF-64 descriptor (paper §II, step 4; Bay et al. 2008 §4.2).
#include <array>

#include "sw/surf/integral_image.h"
#include "sw/surf/keypoint.h"

namespace surfvp::surf {

// Descriptor of the square window of side 20s centred on (kp.x, kp.y) and rotated to
// kp.orientation. The window is 4 x 4 sub-regions of 5 x 5 samples spaced s (sample centres at
// (k - 9.5) s, k = 0..19, along and across the orientation). At each sample, Haar wavelets of
// size 2s give (dx, dy), which are rotated into the window frame: dd along the orientation, dp
// perpendicular to it (+90 degrees), and weighted by a Gaussian of sigma 3.3s centred on the
// point. Each sub-region contributes (sum dd, sum dp, sum |dd|, sum |dp|); sub-regions are in
// row-major order of the window (rows across, columns along the orientation). The 64 values
// are scaled to unit length (all zero for a perfectly flat window).
std::array<float, 64> descriptor(const IntegralView& ii, const Keypoint& kp);

}  // namespace surfvp::surf
