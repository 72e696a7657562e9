#pragma once
// Haar wavelet responses for orientation and description (paper §II, steps 3-4), read from an
// integral-image view (any view type, integral_image.h).
//
// SURF places its wavelets at real positions (multiples of the scale s around a sub-pixel
// interest point) with real sizes (4s, 2s). Rounding them to whole pixels would move a wavelet
// by up to half a pixel and bias it by another half (an even-sized box has no centre pixel),
// which matters at s = 1.6 and breaks rotation covariance. Instead the reference integrates the
// image exactly: the image is taken as constant over each pixel's unit square, and the
// integral over a box with real corners is the bilinear interpolation of the integral image
// (exact for piecewise-constant pixels). Outside the image the pixels are 0, the same clamp
// rule as box_sum().
//
// HaarMode::rounded (params.h) is the embedded alternative, as OpenSURF and the CPU code of the
// paper's time compute it: haar_response_rounded() below, integer corners and integer sums.
#include "sw/surf/integral_image.h"
#include "sw/surf/params.h"

namespace surfvp::surf {

struct HaarResponse {
    float dx = 0;  // right half minus left half
    float dy = 0;  // bottom half minus top half (y grows downwards)
};

namespace haar_detail {

// The helpers are forced inline into haar_response: as templates they would otherwise be
// emitted out of line (the reference, whose helpers had internal linkage, had them inlined),
// which passes the axes through memory and costs the reference ~10 % more instructions.

// One interpolation axis: coordinate c (pixel-centre units) -> integral index i and weight t in
// [0, 1): the integral image is read at i and i + 1.
struct Axis {
    int i;
    float t;
};

[[gnu::always_inline]] inline Axis axis(double c) {
    const double u = c - 0.5;
    int i = static_cast<int>(u);  // truncation, then floor for negatives
    if (u < i) --i;
    return {i, static_cast<float>(u - i)};
}

// area_integral at one corner, split so the large part stays an exact integer:
//   G = I00 + t_x (I10 - I00) + t_y (I01 - I00) + t_x t_y (I11 - I10 - I01 + I00).
// I00 enters the Haar sums as a wrapped uint32 (exact, see integral_image.h); the three
// differences are a column strip, a row strip and one pixel, small enough for float.
struct Corner {
    uint32_t whole;
    float fraction;
};

template <bool kInside, class View>
[[gnu::always_inline]] inline Corner corner(const View& ii, const Axis& ax, const Axis& ay) {
    auto read = [&](int x, int y) { return kInside ? ii.at(x, y) : ii.clamped(x, y); };
    const uint32_t i00 = read(ax.i, ay.i), i10 = read(ax.i + 1, ay.i);
    const uint32_t i01 = read(ax.i, ay.i + 1), i11 = read(ax.i + 1, ay.i + 1);
    const auto col = static_cast<float>(static_cast<int32_t>(i10 - i00));
    const auto row = static_cast<float>(static_cast<int32_t>(i01 - i00));
    const auto pixel = static_cast<float>(static_cast<int32_t>(i11 - i10 - i01 + i00));
    return {i00, ax.t * col + ay.t * row + ax.t * ay.t * pixel};
}

[[gnu::always_inline]] inline bool axis_inside(const Axis& a, int size) { return a.i >= 0 && a.i + 1 < size; }

// dx = right half - left half, dy = bottom half - top half, from the 3 x 3 corner grid
// g[column][row]; the centre corner g[1][1] is needed by neither.
template <bool kInside, class View>
[[gnu::always_inline]] inline HaarResponse haar_from_axes(const View& ii, const Axis (&ax)[3], const Axis (&ay)[3]) {
    uint32_t whole[3][3] = {};
    float fraction[3][3] = {};
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) {
            if (c == 1 && r == 1) continue;
            const Corner g = corner<kInside>(ii, ax[c], ay[r]);
            whole[c][r] = g.whole;
            fraction[c][r] = g.fraction;
        }
    auto dx = [](const auto& g) { return g[2][2] - 2 * g[1][2] - g[2][0] + 2 * g[1][0] + g[0][2] - g[0][0]; };
    auto dy = [](const auto& g) { return g[2][2] - 2 * g[2][1] - g[0][2] + 2 * g[0][1] + g[2][0] - g[0][0]; };
    return {static_cast<float>(static_cast<int32_t>(dx(whole))) + dx(fraction),
            static_cast<float>(static_cast<int32_t>(dy(whole))) + dy(fraction)};
}

// Rounded mode: floor(v) + 1, the integral-image column (row) whose left (top) pixel edge is
// the pixel corner nearest to v (pixel centres at integers, edges at half-integers; ties,
// v an exact integer, go to the corner above). Truncation, then floor for negatives.
[[gnu::always_inline]] inline int nearest_corner(float v) {
    int i = static_cast<int>(v);
    if (v < static_cast<float>(i)) --i;
    return i + 1;
}

// Rounded mode's half-size: round(v) (halves up), at least 1 pixel.
inline int rounded_half(float v) {
    // NOLINTNEXTLINE(bugprone-incorrect-roundings): in float, as the reference rounds; lround differs at x.5-ulp
    const int h = static_cast<int>(v + 0.5f);
    return h < 1 ? 1 : h;
}

// dx, dy from the 3 x 3 grid of integral values at columns x[0..2], rows y[0..2] (the centre
// one is needed by neither): wrap-around uint32 sums (exact, integral_image.h), one int->float
// conversion per response.
template <bool kInside, class View>
[[gnu::always_inline]] inline HaarResponse haar_from_corners(const View& ii, const int (&x)[3], const int (&y)[3]) {
    auto read = [&](int c, int r) { return kInside ? ii.at(x[c], y[r]) : ii.clamped(x[c], y[r]); };
    const uint32_t g00 = read(0, 0), g10 = read(1, 0), g20 = read(2, 0);
    const uint32_t g01 = read(0, 1), g21 = read(2, 1);
    const uint32_t g02 = read(0, 2), g12 = read(1, 2), g22 = read(2, 2);
    const uint32_t dx = g22 - 2 * g12 - g20 + 2 * g10 + g02 - g00;
    const uint32_t dy = g22 - 2 * g21 - g02 + 2 * g01 + g20 - g00;
    return {static_cast<float>(static_cast<int32_t>(dx)), static_cast<float>(static_cast<int32_t>(dy))};
}

}  // namespace haar_detail

// Integral of the image over [-0.5, X) x [-0.5, Y), pixel centres at integers (Keypoint's
// convention), so area_integral(x + 0.5, y + 0.5) == I(x, y) at integer x, y.
template <class View>
double area_integral(const View& ii, double X, double Y) {
    using namespace haar_detail;
    const Axis ax = axis(X), ay = axis(Y);
    const Corner c = corner<false>(ii, ax, ay);
    return static_cast<double>(c.whole) + c.fraction;
}

// The x and y Haar wavelets of side `size` (pixels, real) centred at (x, y): box integrals in
// grey level x pixel^2, not normalised by the area. Reads 8 corners x 4 values = 32 integral
// values (fewer at the border: a negative coordinate reads nothing).
template <class View>
HaarResponse haar_response(const View& ii, float x, float y, float size) {
    using namespace haar_detail;
    const float h = 0.5f * size;
    const Axis ax[3] = {axis(x - h), axis(x), axis(x + h)};
    const Axis ay[3] = {axis(y - h), axis(y), axis(y + h)};
    const bool inside = axis_inside(ax[0], ii.width) && axis_inside(ax[2], ii.width) && axis_inside(ay[0], ii.height) &&
                        axis_inside(ay[2], ii.height);
    return inside ? haar_from_axes<true>(ii, ax, ay) : haar_from_axes<false>(ii, ax, ay);
}

// HaarMode::rounded: the x and y wavelets of side 2 * half (whole pixels) centred on the pixel
// corner nearest to (x, y). With cx = floor(x) + 1 and cy = floor(y) + 1 (that corner lies
// between pixels cx - 1 and cx, cy - 1 and cy), the boxes are pixel columns
// [cx - half, cx - 1] (left) and [cx, cx + half - 1] (right) over rows [cy - half, cy + half - 1],
// and the transposed pair for dy: OpenSURF's haarX(row = cy, column = cx, 2 * half) and haarY.
// OpenSURF takes column = round(x), which puts every wavelet's centre at round(x) - 0.5, half a
// pixel up-left of the sample on average; round(x + 0.5) = floor(x) + 1 (halves up) is the
// nearest corner and has no such bias, and it keeps the wavelets covariant under 90-degree
// rotations. Box integrals in grey level x pixel^2 (the units of haar_response), computed in
// integer arithmetic from the 3 x 3 grid of integral values at columns cx - half - 1, cx - 1,
// cx + half - 1 and the same rows: 8 distinct reads for both wavelets (6 each, 4 shared; fewer
// beyond the top/left border), one int->float conversion per response.
template <class View>
HaarResponse haar_response_rounded(const View& ii, float x, float y, int half) {
    using namespace haar_detail;
    const int cx = nearest_corner(x), cy = nearest_corner(y);
    const int gx[3] = {cx - half - 1, cx - 1, cx + half - 1};
    const int gy[3] = {cy - half - 1, cy - 1, cy + half - 1};
    const bool inside = gx[0] >= 0 && gx[2] < ii.width && gy[0] >= 0 && gy[2] < ii.height;
    return inside ? haar_from_corners<true>(ii, gx, gy) : haar_from_corners<false>(ii, gx, gy);
}

// The Haar pair evaluator for `mode` and wavelet side `size` (pixels), passed to `use` as a
// callable (x, y) -> HaarResponse: exact wavelets of side `size`, or rounded ones of side
// 2 round(size / 2).
template <class View, class Use>
[[gnu::always_inline]] inline auto with_haar(const View& ii, HaarMode mode, float size, Use&& use) {
    if (mode == HaarMode::rounded) {
        const int half = haar_detail::rounded_half(size / 2);
        return use([&](float x, float y) { return haar_response_rounded(ii, x, y, half); });
    }
    return use([&](float x, float y) { return haar_response(ii, x, y, size); });
}

}  // namespace surfvp::surf
