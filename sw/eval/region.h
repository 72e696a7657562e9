#pragma once
// The image region a SURF keypoint stands for, as the evaluation sees it: a circle of radius
// r = 2.5 s about (x, y). The factor 2.5 is the one Bay's SURF library uses when it writes its
// interest points in the Mikolajczyk format (a = c = 1/(2.5 s)^2); no source fixes the
// convention (docs/sources.md#evaluation) [A], so keypoint files and repeatability both take it from here.
#include "sw/surf/keypoint.h"

namespace surfvp::eval {

inline constexpr double kRegionRadiusPerScale = 2.5;

inline double region_radius(double scale) { return kRegionRadiusPerScale * scale; }
inline double region_radius(const surf::Keypoint& keypoint) { return region_radius(keypoint.scale); }

}  // namespace surfvp::eval
