#include "sw/surf/fast_hessian.h"

#include <algorithm>
#include <cstddef>

#include "sw/surf/parallel.h"

namespace surfvp::surf {
namespace {

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

FilterBoxes filter_boxes(int filter_size) {
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

float determinant(int32_t dxx, int32_t dyy, int32_t dxy, float inv_area) {
    const float xx = static_cast<float>(dxx) * inv_area;
    const float yy = static_cast<float>(dyy) * inv_area;
    const float xy = static_cast<float>(dxy) * inv_area;
    return xx * yy - 0.81f * xy * xy;  // (0.9 Dxy)^2, eq. 3
}

// A box as four integral-image offsets from the centre element: sum = +a - b - c + d.
struct Corners {
    ptrdiff_t a, b, c, d;
};

Corners corners(const Box& box, ptrdiff_t stride) {
    return {box.y1 * stride + box.x1, box.y1 * stride + (box.x0 - 1), (box.y0 - 1) * stride + box.x1,
            (box.y0 - 1) * stride + (box.x0 - 1)};
}

struct FilterCorners {
    Corners xx_all, xx_middle, yy_all, yy_middle, xy_tl, xy_tr, xy_bl, xy_br;
};

FilterCorners filter_corners(int filter_size, ptrdiff_t stride) {
    const FilterBoxes f = filter_boxes(filter_size);
    return {corners(f.xx_all, stride),    corners(f.xx_middle, stride), corners(f.yy_all, stride),
            corners(f.yy_middle, stride), corners(f.xy_tl, stride),     corners(f.xy_tr, stride),
            corners(f.xy_bl, stride),     corners(f.xy_br, stride)};
}

// Determinants of `count` samples along one row, `step` pixels apart, starting at `centre`.
// Straight-line integer code on fixed offsets: with kStep known the compiler vectorises it,
// and an AVX2 clone (chosen at load time when the CPU has it) doubles the vector width.
template <int kStep>
__attribute__((target_clones("avx2", "default")))
void determinant_row(const uint32_t* centre, int count, int step, const FilterCorners& fc, float inv_area,
                     float* out) {
    const ptrdiff_t st = kStep > 0 ? kStep : step;
    const FilterCorners f = fc;  // local copy: cannot alias `out`, so the offsets are loop-invariant
    for (int k = 0; k < count; ++k) {
        const uint32_t* p = centre + k * st;
        auto sum = [p](const Corners& c) { return p[c.a] - p[c.b] - p[c.c] + p[c.d]; };
        const auto dxx = static_cast<int32_t>(sum(f.xx_all) - 3u * sum(f.xx_middle));
        const auto dyy = static_cast<int32_t>(sum(f.yy_all) - 3u * sum(f.yy_middle));
        const auto dxy = static_cast<int32_t>(sum(f.xy_tl) + sum(f.xy_br) - sum(f.xy_tr) - sum(f.xy_bl));
        out[k] = determinant(dxx, dyy, dxy, inv_area);
    }
}

// Valid sample range [begin, end) along one axis of `size` pixels for the border rule.
void valid_range(int size, int filter_size, int step, int& begin, int& end) {
    const int b = (filter_size - 1) / 2;
    const int first = b + 1, last = size - 2 - b;  // pixel limits, inclusive
    begin = (first + step - 1) / step;
    end = last >= first ? last / step + 1 : begin;
    if (end < begin) end = begin;
}

// Sets the octave's grid and valid ranges; keeps the planes when the grid is unchanged (values
// outside the valid ranges are then still 0, values inside are all overwritten).
void prepare_octave(int width, int height, int octave, const Params& params, ResponseOctave& oct) {
    oct.octave = octave;
    oct.step = sample_step(octave, params.init_step);
    const int cols = (width + oct.step - 1) / oct.step, rows = (height + oct.step - 1) / oct.step;
    const bool same_grid = cols == oct.cols && rows == oct.rows;
    oct.cols = cols;
    oct.rows = rows;
    oct.layers.resize(static_cast<size_t>(params.intervals));
    for (int i = 0; i < params.intervals; ++i) {
        ResponseLayer& layer = oct.layers[static_cast<size_t>(i)];
        layer.filter_size = filter_size(octave, i);
        valid_range(width, layer.filter_size, oct.step, layer.x_begin, layer.x_end);
        valid_range(height, layer.filter_size, oct.step, layer.y_begin, layer.y_end);
        const size_t n = static_cast<size_t>(cols) * rows;
        if (!same_grid || layer.det.size() != n) layer.det.assign(n, 0.0f);
    }
}

void compute_layer_rows(const IntegralView& ii, int step, int cols, ResponseLayer& layer, int row_begin, int row_end) {
    const FilterCorners fc = filter_corners(layer.filter_size, static_cast<ptrdiff_t>(ii.stride));
    const float inv_area = 1.0f / (static_cast<float>(layer.filter_size) * layer.filter_size);
    const int count = layer.x_end - layer.x_begin;
    for (int ky = std::max(row_begin, layer.y_begin); ky < std::min(row_end, layer.y_end); ++ky) {
        const uint32_t* centre =
            ii.data + static_cast<size_t>(ky) * step * ii.stride + static_cast<size_t>(layer.x_begin) * step;
        float* out = layer.det.data() + static_cast<size_t>(ky) * cols + layer.x_begin;
        switch (step) {
            case 1: determinant_row<1>(centre, count, step, fc, inv_area, out); break;
            case 2: determinant_row<2>(centre, count, step, fc, inv_area, out); break;
            default: determinant_row<0>(centre, count, step, fc, inv_area, out); break;
        }
    }
}

// Octave o, interval j has the filter size of octave o-1, interval 2j+1 on every other sample.
void subsample_layer_rows(const ResponseOctave& prev, int prev_layer, const ResponseOctave& oct, ResponseLayer& layer,
                          int row_begin, int row_end) {
    const std::vector<float>& src = prev.layers[prev_layer].det;
    for (int ky = std::max(row_begin, layer.y_begin); ky < std::min(row_end, layer.y_end); ++ky) {
        const float* in = src.data() + static_cast<size_t>(2 * ky) * prev.cols;
        float* out = layer.det.data() + static_cast<size_t>(ky) * oct.cols;
        for (int kx = layer.x_begin; kx < layer.x_end; ++kx) out[kx] = in[2 * kx];
    }
}

}  // namespace

bool filter_inside(int width, int height, int x, int y, int filter_size) {
    const int b = (filter_size - 1) / 2;
    return x >= b + 1 && y >= b + 1 && x <= width - 2 - b && y <= height - 2 - b;
}

Hessian hessian_at(const IntegralView& ii, int x, int y, int filter_size) {
    const FilterBoxes f = filter_boxes(filter_size);
    auto sum = [&](const Box& b) { return box_sum_inside(ii, x + b.x0, y + b.y0, x + b.x1, y + b.y1); };
    Hessian h;
    h.dxx = sum(f.xx_all) - 3 * sum(f.xx_middle);
    h.dyy = sum(f.yy_all) - 3 * sum(f.yy_middle);
    h.dxy = sum(f.xy_tl) + sum(f.xy_br) - sum(f.xy_tr) - sum(f.xy_bl);
    h.det = determinant(h.dxx, h.dyy, h.dxy, 1.0f / (static_cast<float>(filter_size) * filter_size));
    h.laplacian = h.dxx + h.dyy >= 0 ? 1 : -1;
    return h;
}

ResponseStack compute_responses(const IntegralView& ii, const Params& params, int threads) {
    ResponseStack stack;
    compute_responses(ii, params, threads, stack);
    return stack;
}

void compute_responses(const IntegralView& ii, const Params& params, int threads, ResponseStack& stack) {
    stack.width = ii.width;
    stack.height = ii.height;
    stack.octaves.resize(static_cast<size_t>(params.octaves));
    for (int o = 0; o < params.octaves; ++o) {
        ResponseOctave& oct = stack.octaves[static_cast<size_t>(o)];
        prepare_octave(ii.width, ii.height, o, params, oct);
        const ResponseOctave* prev = o > 0 ? &stack.octaves[static_cast<size_t>(o) - 1] : nullptr;
        parallel_for(oct.rows, threads, [&](int row_begin, int row_end) {
            for (int i = 0; i < params.intervals; ++i) {
                ResponseLayer& layer = oct.layers[static_cast<size_t>(i)];
                if (layer.empty()) continue;
                if (prev && 2 * i + 1 < params.intervals)
                    subsample_layer_rows(*prev, 2 * i + 1, oct, layer, row_begin, row_end);
                else
                    compute_layer_rows(ii, oct.step, oct.cols, layer, row_begin, row_end);
            }
        });
    }
}

}  // namespace surfvp::surf
