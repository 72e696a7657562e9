#pragma once
// A SURF interest point with its descriptor: what the float reference SURF, the chip's
// software stage and the evaluation all exchange.
#include <array>
#include <vector>

namespace surfvp::surf {

struct Keypoint {
    float x = 0;                         // column, pixels; (0, 0) is the centre of the top-left pixel
    float y = 0;                         // row, pixels
    float scale = 0;                     // s = 1.2 L / 9 for a box filter of size L (interpolated)
    float orientation = 0;               // radians, counter-clockwise from +x in image axes; 0 when upright
    float response = 0;                  // Hessian determinant (area-normalised, image in 0..255)
    int laplacian = 0;                   // +1 or -1: the sign of the Hessian's trace (0: unknown)
    std::array<float, 64> descriptor{};  // unit length when computed; all zero when not
};

using Keypoints = std::vector<Keypoint>;

}  // namespace surfvp::surf
