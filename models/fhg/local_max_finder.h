#pragma once
// LocMaxFinder (paper §III-C, Fig. 8): thresholds the determinants and suppresses
// non-maxima, but only among the neighbours present in two adjacent determinant blocks (the
// current block and the one before it in the same block row): it "doesn't have sufficient
// memory resources to store all data needed to examine whole neighborhood". It therefore
// marks every true 3x3x3 maximum and some points that are not; the software re-checks all
// 26 neighbours. Plain C++.
//
// Candidate scales are the middle intervals of each octave: octave 1 sizes 15 and 21
// (neighbours in scale: 9..27, step 1), octave 2 sizes 27 and 39 (15..51, step 2, at the
// blocks' even pixels). A point is marked when its determinant is above the threshold and
// strictly above every available neighbour.
#include <cstdint>
#include <vector>

#include "filter_geometry.h"

namespace surfvp::fhg {

struct Candidate {
    int x = 0, y = 0;    // pixel
    int size_index = 0;  // into kSizes: 1 (15), 2 (21), 3 (27, octave 2), 4 (39, octave 2)
    bool operator==(const Candidate& o) const { return x == o.x && y == o.y && size_index == o.size_index; }
    int octave() const { return size_index >= 3 ? 2 : 1; }
};

// The maxima FIFO word (fhg_regs.h): [31] valid, [27] octave 2, [26:24] size index,
// [23:12] y, [11:0] x.
uint32_t pack_candidate(const Candidate& c);
Candidate unpack_candidate(uint32_t word);

class LocalMaxFinder {
public:
    explicit LocalMaxFinder(int32_t threshold) : threshold_(threshold) {}

    // One block: `current` and `left` are 18-determinant block records (left: nullptr at the
    // start of a block row). Appends candidates in a fixed order.
    void block(const int32_t* current, const int32_t* left, int bx, int by, std::vector<Candidate>& out) const;
    // A block row of `blocks` records as HessianCore::block_row writes them.
    void block_row(const int32_t* records, int blocks, int by, std::vector<Candidate>& out) const;

private:
    int32_t threshold_;
};

}  // namespace surfvp::fhg
