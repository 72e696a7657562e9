#pragma once
// One keypoint per blob. A blob can be a maximum in two octaves or two adjacent layers (with 5
// filter sizes per octave, a size is a middle layer of both octaves that share it), and both
// maxima interpolate to nearly the same point: twins. They would count twice in a keypoint
// budget and match each other's descriptor, so the float reference keeps the stronger.
#include <cstddef>

#include "sw/surf/keypoint.h"

namespace surfvp::surf {

// Twins: centres within this distance, in pixels, and scales within this ratio (the larger
// over the smaller). [A] half a pixel is below the interpolation's own spread at the finest
// scale; 1.3 is less than the ratio of adjacent filter sizes of one octave at octave 0 (15/9 =
// 1.67), so two real blobs nested at different scales are kept apart.
constexpr float kTwinDistancePx = 0.5f;
constexpr float kTwinScaleRatio = 1.3f;

bool twins(const Keypoint& a, const Keypoint& b);

// Removes every keypoint that has a stronger twin (the first of equal responses stays); the
// others keep their order.
void drop_twins(Keypoints& keypoints);

// The share of keypoints that have a twin among the others (0 for fewer than 2).
double twin_share(const Keypoints& keypoints);

}  // namespace surfvp::surf
