#pragma once
// Haar wavelet responses for orientation and description (paper §II, steps 3-4), read from an
// integral-image view.
//
// SURF places its wavelets at real positions (multiples of the scale s around a sub-pixel
// interest point) with real sizes (4s, 2s). Rounding them to whole pixels would move a wavelet
// by up to half a pixel and bias it by another half (an even-sized box has no centre pixel),
// which matters at s = 1.6 and breaks rotation covariance. Instead the reference integrates the
// image exactly: the image is taken as constant over each pixel's unit square, and the
// integral over a box with real corners is the bilinear interpolation of the integral image
// (exact for piecewise-constant pixels). Outside the image the pixels are 0, the same clamp
// rule as box_sum().
#include "sw/surf/integral_image.h"

namespace surfvp::surf {

// Integral of the image over [-0.5, X) x [-0.5, Y), pixel centres at integers (Keypoint's
// convention), so area_integral(x + 0.5, y + 0.5) == I(x, y) at integer x, y.
double area_integral(const IntegralView& ii, double X, double Y);

struct HaarResponse {
    float dx = 0;  // right half minus left half
    float dy = 0;  // bottom half minus top half (y grows downwards)
};

// The x and y Haar wavelets of side `size` (pixels, real) centred at (x, y): box integrals in
// grey level x pixel^2, not normalised by the area.
HaarResponse haar_response(const IntegralView& ii, float x, float y, float size);

}  // namespace surfvp::surf
