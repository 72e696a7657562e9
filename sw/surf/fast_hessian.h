#pragma once
// Fast-Hessian detector, step 2 of the paper's §II: box-filter approximations of the Gaussian
// second derivatives, their area-normalised determinant (eq. 3), on a stack of filter sizes.
//
// Filter geometry (Bay et al., CVIU 2008, §3.3; paper Table I). Octave o and interval i are
// 0-based: L = 3 * (2^(o+1) * (i+1) + 1), i.e. 9 15 21 27 / 15 27 39 51 / 27 51 75 99 /
// 51 99 147 195; lobe l = L / 3; scale s = 1.2 L / 9; sampling step = init_step * 2^o.
//
// Units: responses are box sums on the 0..255 image divided by the filter area L^2, as in the
// SURF papers and OpenSURF, so the determinant Dxx Dyy - (0.9 Dxy)^2 is OpenSURF's value (0..1
// image) times 255^2. Both use 0..255 images, but it is NOT numerically OpenCV's SURF
// `hessianThreshold`: OpenCV divides each box by its own area (l(2l-1) for a Dxx/Dyy lobe,
// l^2 for a Dxy quadrant), which makes its determinant (9l / (2l-1))^2 = 29 (L = 9) .. 21
// (L = 195) times this one at a blob centre (Dxy = 0) and not proportional elsewhere. As a rule
// of thumb divide an OpenCV threshold by ~20-25 (README.md).
//
// Border rule: a response at pixel (x, y) exists only when the L x L filter and one more pixel
// on every side lie inside the image, i.e. b + 1 <= x <= width - 2 - b with b = (L - 1) / 2
// (same for y). The box sums read the integral image one row and column before the filter
// (the paper's footnote 3: a 51-filter needs a 52 x 52 area); keeping that pixel on all four
// sides makes the rule symmetric, so detection commutes with 90-degree rotations.
#include <cstdint>
#include <vector>

#include "sw/surf/integral_image.h"
#include "sw/surf/params.h"

namespace surfvp::surf {

inline int filter_size(int octave, int interval) { return 3 * ((2 << octave) * (interval + 1) + 1); }
inline int sample_step(int octave, int init_step) { return init_step << octave; }
inline float filter_scale(float filter_size) { return 1.2f * filter_size / 9.0f; }
// Filter-size spacing between consecutive intervals of an octave: 6 * 2^o.
inline int filter_spacing(int octave) { return 6 << octave; }

// The filter responses at one pixel, computed point by point (the readable reference form).
struct Hessian {
    int32_t dxx = 0, dyy = 0, dxy = 0;  // raw box-filter sums (weights 1, -2, 1 and +-1)
    float det = 0;                      // area-normalised determinant, eq. 3 with 0.9^2 = 0.81
    int laplacian = 0;                  // sign of the trace Dxx + Dyy: +1 dark blob, -1 bright
};

// True when the filter of size L centred on (x, y) satisfies the border rule above.
bool filter_inside(int width, int height, int x, int y, int filter_size);

namespace hessian_detail {

// An inclusive box relative to the filter centre: columns [x0, x1], rows [y0, y1].
struct Box {
    int x0, y0, x1, y1;
};

// The eight boxes of the three filters of size L (Bay et al. 2008, Fig. 1). Dyy is three
// vertically stacked lobes of l rows and 2l - 1 columns with weights +1, -2, +1; written as
// Box(all three) - 3 Box(middle) it needs two boxes instead of three (paper, footnote 2) and the
// integer result is identical. Dxx is Dyy transposed. Dxy is four l x l boxes around the centre
// row and column, +1 top-left and bottom-right, -1 top-right and bottom-left.
struct FilterBoxes {
    Box xx_all, xx_middle, yy_all, yy_middle, xy_tl, xy_tr, xy_bl, xy_br;
};

inline FilterBoxes filter_boxes(int filter_size) {
    const int l = filter_size / 3;        // lobe
    const int b = (filter_size - 1) / 2;  // half extent of the whole filter
    const int h = (l - 1) / 2;            // half extent of the middle lobe (l is odd)
    FilterBoxes f{};
    f.yy_all = {-(l - 1), -b, l - 1, b};
    f.yy_middle = {-(l - 1), -h, l - 1, h};
    f.xx_all = {-b, -(l - 1), b, l - 1};
    f.xx_middle = {-h, -(l - 1), h, l - 1};
    f.xy_tl = {-l, -l, -1, -1};
    f.xy_tr = {1, -l, l, -1};
    f.xy_bl = {-l, 1, -1, l};
    f.xy_br = {1, 1, l, l};
    return f;
}

inline float determinant(int32_t dxx, int32_t dyy, int32_t dxy, float inv_area) {
    const float xx = static_cast<float>(dxx) * inv_area;
    const float yy = static_cast<float>(dyy) * inv_area;
    const float xy = static_cast<float>(dxy) * inv_area;
    return xx * yy - 0.81f * xy * xy;  // (0.9 Dxy)^2, eq. 3
}

}  // namespace hessian_detail

// Responses at (x, y) for filter size L; the caller guarantees filter_inside(). Any
// integral-image view type (integral_image.h): 8 boxes, 32 reads.
template <class View>
Hessian hessian_at(const View& ii, int x, int y, int filter_size) {
    using hessian_detail::Box;
    const hessian_detail::FilterBoxes f = hessian_detail::filter_boxes(filter_size);
    auto sum = [&](const Box& b) { return box_sum_inside(ii, x + b.x0, y + b.y0, x + b.x1, y + b.y1); };
    Hessian h;
    h.dxx = sum(f.xx_all) - 3 * sum(f.xx_middle);
    h.dyy = sum(f.yy_all) - 3 * sum(f.yy_middle);
    h.dxy = sum(f.xy_tl) + sum(f.xy_br) - sum(f.xy_tr) - sum(f.xy_bl);
    h.det = hessian_detail::determinant(h.dxx, h.dyy, h.dxy, 1.0f / (static_cast<float>(filter_size) * filter_size));
    h.laplacian = h.dxx + h.dyy >= 0 ? 1 : -1;
    return h;
}

// One filter size sampled on its octave's grid: sample (kx, ky) is pixel (kx*step, ky*step).
// Determinants are stored for the whole grid; outside [x_begin, x_end) x [y_begin, y_end)
// (the border rule) they are 0 and never used.
struct ResponseLayer {
    int filter_size = 0;
    int x_begin = 0, x_end = 0, y_begin = 0, y_end = 0;  // valid sample indices, half-open
    std::vector<float> det;                              // cols * rows, row-major

    bool empty() const { return x_begin >= x_end || y_begin >= y_end; }
};

struct ResponseOctave {
    int octave = 0;
    int step = 1;
    int cols = 0, rows = 0;             // grid size: ceil(width / step) x ceil(height / step)
    std::vector<ResponseLayer> layers;  // one per interval

    float at(int layer, int kx, int ky) const { return layers[layer].det[static_cast<size_t>(ky) * cols + kx]; }
};

struct ResponseStack {
    int width = 0, height = 0;
    std::vector<ResponseOctave> octaves;
};

// All determinants for params.octaves x params.intervals filter sizes. Each octave's rows are
// split over `threads`. Filter sizes an octave shares with the previous one (octave o, interval
// j == octave o-1, interval 2j+1) are subsampled from it, as the chip does (paper §III-C).
ResponseStack compute_responses(const IntegralView& ii, const Params& params, int threads);
// Same, into `stack`, reusing its planes when the grid sizes are unchanged (frame streams).
void compute_responses(const IntegralView& ii, const Params& params, int threads, ResponseStack& stack);

}  // namespace surfvp::surf
