#pragma once
// SSA FHG's arithmetic (paper §III-C): the integer Hessian determinants of one 2x2
// determinant block, exactly as the TripleMACs and HessianCalc form them. Plain C++.
//
// Per determinant of filter size L at pixel (x, y):
//   1. TripleMAC: Dxx, Dyy, Dxy as integer sums of integral-image reads times 1, -1, 3, -3
//      (filter_geometry.h), in an `accumulator_bits` two's-complement accumulator.
//      The sums wrap like the hardware's; the result is exact while it fits.
//   2. Area normalisation: r = round(D x K_L / 2^recip_shift), K_L = round(2^(F + recip_shift) / L^2):
//      responses with F = response_frac_bits fraction bits, saturated to response_bits.
//   3. HessianCalc: det = rxx ryy - round(W rxy^2 / 2^weight_frac_bits), W = round(0.81 x 2^weight_frac_bits),
//      (2F fraction bits), rounded to det_frac_bits fraction bits and saturated to det_bits.
// A determinant whose filter does not lie inside the image (x or y closer than (L-1)/2 to
// an edge) is 0: the hardware never reads outside the image.
// Rounding is half up (add half, arithmetic shift right).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "filter_geometry.h"
#include "models/iig/integral_core.h"

namespace surfvp::fhg {

struct Precision {
    unsigned accumulator_bits = 24;
    unsigned recip_shift = 16;
    unsigned response_frac_bits = 9;
    unsigned response_bits = 18;
    unsigned weight_frac_bits = 12;
    unsigned det_frac_bits = 16;
    unsigned det_bits = 32;
};

class HessianCore {
public:
    explicit HessianCore(const Precision& precision);  // throws std::invalid_argument naming the field

    struct Sums {
        int64_t xx, yy, xy;  // the TripleMAC accumulators (after wrapping to accumulator_bits)
    };
    Sums sums(const IntegralView& ii, int x, int y, int size) const;
    int32_t determinant(const IntegralView& ii, int x, int y, int size) const;
    std::array<int32_t, kDeterminantsPerBlock> block(const IntegralView& ii, int bx, int by) const;
    // Every block of block row `by`: out[bx * 18 + k]; `out` holds ceil(width / 2) x 18 values.
    void block_row(const IntegralView& ii, int by, int32_t* out) const;

    // The same determinants as the image rows give them: octave 1's size index i at image row
    // 2 by + py for every pixel (`octave1[i][py]`, two a block) and octave 2's j at the blocks'
    // pixel (0, 0) (`octave2[j]`). at(bx, k) is block bx's record position k. Writing the records
    // from these once, block by block, costs a third of scattering them line by line.
    struct Lines {
        int blocks = 0;
        const int32_t* octave1[4][2] = {};
        const int32_t* octave2[2] = {};
        int32_t at(int bx, int k) const {
            return k < 16 ? octave1[k / 4][k / 2 % 2][2 * bx + k % 2] : octave2[k - 16][bx];
        }
        void record(int bx, int32_t* out) const {  // block bx's 18 determinants
            for (int k = 0; k < kDeterminantsPerBlock; ++k) out[k] = at(bx, k);
        }
    };
    // The lines are the calling thread's until its next call. With `peaks`, each block's largest
    // determinant at the positions LocalMaxFinder tests (tested_by_finder).
    Lines block_row_lines(const IntegralView& ii, int by, int32_t* peaks = nullptr) const;

    double to_float(int64_t det) const { return double(det) / double(int64_t(1) << precision_.det_frac_bits); }
    int32_t from_float(double det) const;  // a threshold in OpenCV's units, as the hardware compares it
    static bool inside(int width, int height, int x, int y, int size) {
        const int b = (size - 1) / 2;
        return x >= b && y >= b && x + b < width && y + b < height;
    }
    const Precision& precision() const { return precision_; }
    int64_t reciprocal(int size) const { return reciprocal_[size_t(size)]; }  // K_L
    int64_t weight() const { return weight_; }                                // W

    // One response along an image row: sum(x) = sum of tap_j x P(x + dx_j), where
    // P(x) = sum of weight_i x I(x, y + dy_i) (the row path's form of filter_reads).
    struct Factors {
        int rows = 0, taps = 0;
        std::array<int, 4> dy{}, weight{}, dx{}, tap{};
        // Each sum's terms as pairs of equal and opposite weights, those of magnitude 1 first:
        // the terms' indices (-1: a zero row) and the pair's magnitude.
        struct Pairing {
            int count = 0, units = 0;
            std::array<int, 4> plus{}, minus{};
            std::array<uint32_t, 4> magnitude{};
        };
        Pairing row_pairs, tap_pairs;
    };

private:
    int32_t finish(int64_t xx, int64_t yy, int64_t xy, int size) const;  // steps 2 and 3
    int64_t wrap(int64_t sum) const;
    // One image row at filter `size`: dets at x = x0 + k step for k < count into out[k].
    void row(const IntegralView& ii, int y, int size, int x0, int step, int count, int32_t* out) const;

    Precision precision_;
    int64_t weight_;
    std::array<int64_t, 64> reciprocal_{};              // K_L indexed by L
    std::array<std::vector<Read>, 64> reads_;           // filter_reads(L) indexed by L
    std::array<std::array<Factors, 3>, 64> factors_{};  // the reads as a row's Factors, by L and Response
    bool double_exact_ = false;                         // the row path may finish in double precision
};

}  // namespace surfvp::fhg
