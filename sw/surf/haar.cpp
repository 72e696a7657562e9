#include "sw/surf/haar.h"

namespace surfvp::surf {
namespace {

// One interpolation axis: coordinate c (pixel-centre units) -> integral index i and weight t in
// [0, 1): the integral image is read at i and i + 1.
struct Axis {
    int i;
    float t;
};

Axis axis(double c) {
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

template <bool kInside>
Corner corner(const IntegralView& ii, const Axis& ax, const Axis& ay) {
    auto read = [&](int x, int y) { return kInside ? ii.at(x, y) : ii.clamped(x, y); };
    const uint32_t i00 = read(ax.i, ay.i), i10 = read(ax.i + 1, ay.i);
    const uint32_t i01 = read(ax.i, ay.i + 1), i11 = read(ax.i + 1, ay.i + 1);
    const auto col = static_cast<float>(static_cast<int32_t>(i10 - i00));
    const auto row = static_cast<float>(static_cast<int32_t>(i01 - i00));
    const auto pixel = static_cast<float>(static_cast<int32_t>(i11 - i10 - i01 + i00));
    return {i00, ax.t * col + ay.t * row + ax.t * ay.t * pixel};
}

bool axis_inside(const Axis& a, int size) { return a.i >= 0 && a.i + 1 < size; }

// dx = right half - left half, dy = bottom half - top half, from the 3 x 3 corner grid
// g[column][row]; the centre corner g[1][1] is needed by neither.
template <bool kInside>
HaarResponse haar_from_axes(const IntegralView& ii, const Axis (&ax)[3], const Axis (&ay)[3]) {
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

}  // namespace

double area_integral(const IntegralView& ii, double X, double Y) {
    const Axis ax = axis(X), ay = axis(Y);
    const Corner c = corner<false>(ii, ax, ay);
    return static_cast<double>(c.whole) + c.fraction;
}

HaarResponse haar_response(const IntegralView& ii, float x, float y, float size) {
    const float h = 0.5f * size;
    const Axis ax[3] = {axis(x - h), axis(x), axis(x + h)};
    const Axis ay[3] = {axis(y - h), axis(y), axis(y + h)};
    const bool inside = axis_inside(ax[0], ii.width) && axis_inside(ax[2], ii.width) && axis_inside(ay[0], ii.height) &&
                        axis_inside(ay[2], ii.height);
    return inside ? haar_from_axes<true>(ii, ax, ay) : haar_from_axes<false>(ii, ax, ay);
}

}  // namespace surfvp::surf
