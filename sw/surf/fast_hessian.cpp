#include "sw/surf/fast_hessian.h"

#include <algorithm>
#include <cstddef>

#include "sw/surf/parallel.h"

namespace surfvp::surf {
namespace {

using hessian_detail::Box;
using hessian_detail::determinant;
using hessian_detail::filter_boxes;
using hessian_detail::FilterBoxes;

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
#if !defined(__clang__)  // clang 14 cannot multiversion a template (the fuzz build): the default version only
__attribute__((target_clones("avx2", "default")))
#endif
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
            case 1:
                determinant_row<1>(centre, count, step, fc, inv_area, out);
                break;
            case 2:
                determinant_row<2>(centre, count, step, fc, inv_area, out);
                break;
            default:
                determinant_row<0>(centre, count, step, fc, inv_area, out);
                break;
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
