#pragma once
// Non-maximum suppression in the 3x3x3 scale-space neighbourhood (paper §II, step 2).
#include <vector>

#include "sw/surf/fast_hessian.h"

namespace surfvp::surf {

// A determinant that beats its 26 neighbours, in its octave's sample grid.
struct LocalMaximum {
    int octave = 0;
    int layer = 0;  // interval, 1 .. intervals - 2 (the outer two only serve as neighbours)
    int kx = 0, ky = 0;
    float response = 0;
};

// Every sample with det > threshold that is strictly greater than all 26 neighbours (8 in its
// own layer, 9 in each adjacent layer of the same octave). Ties are not maxima: a plateau gives
// no interest point. Only samples whose whole neighbourhood was computed are candidates, i.e.
// the border rule of the larger adjacent filter applies, shrunk by one sample.
// Rows are split over `threads`; the result is in (octave, layer, row, column) order whatever
// the thread count.
std::vector<LocalMaximum> find_local_maxima(const ResponseStack& stack, float threshold, int threads);

}  // namespace surfvp::surf
