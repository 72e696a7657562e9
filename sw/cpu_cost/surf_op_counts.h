#pragma once
// What one step of the software stage costs, in operations (cost_model.h), tallied from the
// code that runs: sw/surf's haar.h, orientation.h, descriptor.h, interpolation.cpp,
// fast_hessian.h (hessian_at) and sw/stage. The integral-image and determinant reads are NOT
// in these mixes: the probe counts each one as it happens, with its address, so border effects
// (fewer reads) and the cache are exact. Tallies assume a straightforward PowerPC compilation
// of that code (32 FPRs, values kept in registers within a step, no fused multiply-add); the
// README explains each line.
#include "sw/cpu_cost/cost_model.h"

namespace surfvp::sw::surf_ops {

// haar_response(): the x and y wavelets at a real position and size, from 8 corners of
// bilinearly interpolated integral values (32 reads, counted by the probe).
//   half size, 6 coordinates       1 fmul, 4 fadd
//   6 axes (floor, fraction)       12 fadd, 12 fcvt, 6 fcmp, 6 int, 6 branch
//   inside test                    8 int, 4 branch
//   8 corners                      64 int (addresses, 3 integer differences), 24 fcvt, 24 fmul, 16 fadd
//   dx, dy from the corners        14 int, 12 fadd, 4 fmul, 2 fcvt
constexpr OpCounts kHaarWavelet{{Op::fadd, 44}, {Op::fmul, 29}, {Op::fcvt, 38}, {Op::fcmp, 6},
                                {Op::int_op, 92}, {Op::branch, 10}};

// HaarMode::rounded, haar_response_rounded(): the x and y wavelets of whole size 2 half centred
// on the pixel corner nearest to a real position, from the 3 x 3 grid of integral values
// (8 distinct reads, counted by the probe; 6 per wavelet, 4 shared).
//   2 corner indices floor(v) + 1   truncation and back for the test: 4 fcvt, 2 fcmp, 2 branch,
//                                   decrement and + 1: 4 int
//   6 grid coordinates              6 int
//   inside test                     8 int, 4 branch
//   8 addresses                     3 row bases 6 int, 3 column offsets 3 int, 8 adds 8 int
//   dx, dy in integers              14 int (5 add/sub and 2 shifts each)
//   the two responses to float      2 fcvt
constexpr OpCounts kHaarWaveletRounded{{Op::fcvt, 6}, {Op::fcmp, 2}, {Op::int_op, 49}, {Op::branch, 6}};
// HaarMode::rounded, once per orientation: the half-size round(2s), at least 1 (1 fmul, 1 fadd,
// truncation 1 fcvt, the minimum 2 int + 1 branch).
constexpr OpCounts kOrientationSetupRounded{{Op::fmul, 1}, {Op::fadd, 1}, {Op::fcvt, 1}, {Op::int_op, 2},
                                            {Op::branch, 1}};

// orientation(): one of the 109 samples, besides its wavelet.
//   position x + i s, y + j s      2 fcvt, 2 fmul, 2 fadd, 2 int (grid entry)
//   weight, weighted dx, dy        1 gaussian_weight, 2 fmul
//   zero test                      2 fcmp, 1 branch
//   angle: atan2, wrap_angle       1 atan2; fmod (early return for |a| < 2 pi): 12 int, 3 branch,
//                                  1 fstore, 1 fload; sign fix 1 fcmp, 1 fadd
//   bin index                      1 fmul, 1 fcvt, 1 int, 1 branch
//   bin sums (72 bins: memory)     2 fload, 2 fadd, 2 fstore, 2 int
//   loop                           2 int, 1 branch
constexpr OpCounts kOrientationSample{{Op::fcvt, 3},   {Op::fmul, 5},   {Op::fadd, 5},  {Op::fcmp, 3},
                                      {Op::fload, 3},  {Op::fstore, 3}, {Op::int_op, 19}, {Op::branch, 6},
                                      {Op::gaussian_weight, 1}, {Op::atan2, 1}};
// One of the 36 window positions: 6 bins (2 fload, 2 fadd, 3 int, 1 branch each), the length
// 2 fmul + 1 fadd, compare 1 fcmp + 1 branch, loop 1 int + 1 branch.
constexpr OpCounts kOrientationWindow{{Op::fload, 12}, {Op::fadd, 13}, {Op::fmul, 2}, {Op::fcmp, 1},
                                      {Op::int_op, 19}, {Op::branch, 8}};
// The winning window's angle: atan2 + wrap_angle, and the best_len2 > 0 test.
constexpr OpCounts kOrientationFinish{{Op::atan2, 1}, {Op::fcmp, 2}, {Op::fadd, 1}, {Op::fload, 1},
                                      {Op::fstore, 1}, {Op::int_op, 12}, {Op::branch, 4}};

// descriptor(): cos and sin of the orientation, the wavelet size 2s.
constexpr OpCounts kDescriptorSetup{{Op::sin_cos, 2}, {Op::fmul, 1}};
// HaarMode::rounded: cos and sin, the half-size round(s), at least 1 (no multiplication).
constexpr OpCounts kDescriptorSetupRounded{{Op::sin_cos, 2}, {Op::fadd, 1}, {Op::fcvt, 1}, {Op::int_op, 2},
                                           {Op::branch, 1}};
// One of the 400 samples, besides its wavelet.
//   offset u = (k - 9.5) s          1 fcvt, 1 fadd, 1 fmul
//   rotated position px, py         4 fmul, 4 fadd
//   weight; dd, dp                  1 gaussian_weight; 6 fmul, 2 fadd
//   sub-region index                6 int (two divisions by 5 as multiply-shift)
//   4 sums in memory, 2 fabs        4 fload, 4 fadd, 4 fstore, 2 fmove
//   loop                            1 int, 1 branch
constexpr OpCounts kDescriptorSample{{Op::fcvt, 1},   {Op::fadd, 11},  {Op::fmul, 11},  {Op::fload, 4},
                                     {Op::fstore, 4}, {Op::fmove, 2},  {Op::int_op, 7}, {Op::branch, 1},
                                     {Op::gaussian_weight, 1}};
// Unit length: sum of squares (64 x fload, fmul, fadd), 1 fsqrt, 1 fdiv, scale (64 x fload,
// fmul, fstore), test and loops.
constexpr OpCounts kDescriptorNormalise{{Op::fload, 128}, {Op::fmul, 128}, {Op::fadd, 64},  {Op::fstore, 64},
                                        {Op::fsqrt, 1},   {Op::fdiv, 1},   {Op::fcmp, 1},   {Op::int_op, 128},
                                        {Op::branch, 129}};

// hessian_at() for the Laplacian sign: 8 boxes (32 reads, counted by the probe; 15 int each
// for corners and sums), filter geometry 12 int, Dxx/Dyy/Dxy 7 int, the determinant 4 fcvt,
// 1 fdiv, 7 fmul, 1 fadd, the sign 1 int + 1 branch.
constexpr OpCounts kHessianAt{{Op::int_op, 140}, {Op::fcvt, 4}, {Op::fmul, 7}, {Op::fadd, 1},
                              {Op::fdiv, 1},     {Op::branch, 2}};

// sw/stage: a FIFO word's fields, validity and size index.
constexpr OpCounts kCandidateDecode{{Op::int_op, 8}, {Op::branch, 3}};
// Whether the 3x3x3 neighbourhood lies inside the image and every filter in it fits.
constexpr OpCounts kBorderCheck{{Op::int_op, 8}, {Op::branch, 4}};
// One determinant compared (the centre with the threshold, or with a neighbour): its record
// address 3 int, the compare 1 int, 1 branch. The load itself is counted by the probe.
constexpr OpCounts kDeterminantCompare{{Op::int_op, 4}, {Op::branch, 1}};

// interpolate_maximum() on the 27 values (interpolation.cpp):
//   27 values to threshold units     27 fcvt, 27 fmul, 27 fstore; 19 fload to use them
//   gradient, Hessian                18 fadd, 9 fmul
//   3x3 inverse with check (Eigen)   30 fmul, 11 fadd, 1 fdiv, 1 fcmp, 1 fmove
//   offset -H^-1 g                   9 fmul, 6 fadd, 3 fmove
//   finite, |offset| <= 0.5          3 fadd, 6 fcmp, 3 fmove
//   indexing, calls, tests           20 int, 6 branch
constexpr OpCounts kInterpolationSolve{{Op::fcvt, 27}, {Op::fmul, 75},   {Op::fadd, 38},   {Op::fdiv, 1},
                                       {Op::fcmp, 7},  {Op::fmove, 7},   {Op::fload, 19},  {Op::fstore, 27},
                                       {Op::int_op, 20}, {Op::branch, 6}};
// An accepted offset to a keypoint: x, y (2 fcvt, 2 fmul, 4 fadd), scale 1.2 (L + o_s dL) / 9
// (2 fcvt, 2 fmul, 1 fadd, 1 fdiv).
constexpr OpCounts kKeypointFinish{{Op::fcvt, 4}, {Op::fmul, 4}, {Op::fadd, 5}, {Op::fdiv, 1},
                                   {Op::int_op, 4}, {Op::branch, 1}};

// Per keypoint, how many of each: sw/surf's sampling grids.
constexpr int kOrientationSamples = 109;  // i^2 + j^2 < 36 (orientation.h)
constexpr int kOrientationWindows = 36;   // pi/18 steps
constexpr int kDescriptorSamples = 400;   // 20 x 20 (descriptor.h)

}  // namespace surfvp::sw::surf_ops
