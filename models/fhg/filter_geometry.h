#pragma once
// The box filters of the Fast-Hessian detector as the FHG forms them (paper §II, footnote 2;
// docs/sources.md#surf and #arithmetic). Shared by HessianCore (which adds them up) and the
// SequenceGenerator (which schedules their integral-image reads). Plain C++.
//
// A filter of size L (9, 15, 21, 27, 39, 51) has lobe l = L/3 and half-width b = (L-1)/2,
// and is centred on a pixel. With the -3 trick, Dxx is the whole L x (2l-1) box minus three
// times its l x (2l-1) middle lobe (two boxes, 8 reads) instead of three lobes weighted
// 1, -2, 1; Dyy is its transpose; Dxy is four l x l quadrants around the centre row and
// column, weighted +1 (top-right, bottom-left) and -1 (top-left, bottom-right): 16 reads.
// 32 integral-image reads per determinant.
#include <array>
#include <vector>

namespace surfvp::fhg {

enum class Response { xx = 0, yy = 1, xy = 2 };

// A box of pixels [x0, x1] x [y0, y1] relative to the filter centre, inclusive, with weight.
struct Box {
    int x0, y0, x1, y1;
    int weight;
};

// One integral-image read: the value I(dx, dy) relative to the centre (I is the inclusive
// integral image, I(x, y) = sum of pixels (i <= x, j <= y); I(-1, .) = I(., -1) = 0), times
// `coefficient` (+1, -1, +3 or -3), added to `response`.
struct Read {
    int dx, dy;
    int coefficient;
    Response response;
};

std::vector<Box> filter_boxes(int size, Response response);
std::vector<Read> filter_reads(int size);  // all 32, in a fixed order: xx, yy, xy

// The filter sizes of the two octaves the hardware covers, and the determinants of one
// 2x2 block: octave 1 (sizes 9, 15, 21, 27) at each of the four pixels, octave 2 (sizes 39
// and 51) at the block's top-left pixel only (step 2); octave 2's sizes 15 and 27 are
// octave 1's values at the even pixels.
constexpr std::array<int, 6> kSizes = {9, 15, 21, 27, 39, 51};
constexpr int kDeterminantsPerBlock = 18;

struct BlockDeterminant {
    int size;    // filter size L
    int px, py;  // pixel within the block (0 or 1 each)
};
// Index k in 0..17 of the determinant buffer's block record (fhg_regs.h documents it):
// k = 4 i + (2 py + px) for octave 1 size index i (0..3), k = 16 + j for octave 2 size 39 (j = 0), 51 (j = 1).
BlockDeterminant block_determinant(int k);
// The record positions LocalMaxFinder compares with the threshold (its candidate scales):
// octave 1's sizes 15 and 21 at the four pixels (k = 4..11), octave 2's 27 and 39 at pixel
// (0, 0) (k = 12, 16). A block none of them exceeds marks nothing.
constexpr bool tested_by_finder(int k) { return (k >= 4 && k <= 12) || k == 16; }

// The integral-image window one block reads, relative to its pixel (0, 0): from -26 (L = 51:
// b = 25, plus the row/column before the box) to +25 (L = 51's far edge; octave 1's L = 27 at
// pixel 1 reaches only +14). 52 x 52 values: the paper's "52 x 52 pixels" (§III-C, note 3).
constexpr int kReachBefore = 26;
constexpr int kReachAfter = 25;
constexpr int kWindow = kReachBefore + kReachAfter + 1;

}  // namespace surfvp::fhg
