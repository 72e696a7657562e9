#pragma once
// The MasterController's "control and addressing sequence" (paper §III-C, Fig. 6, note 4):
// the order in which the read buses deliver integral-image values of one 2x2 determinant
// block to the TripleMACs, generated here from the filter geometry instead of being taken
// as a number. Plain C++.
//
// The machine it schedules:
// - `read_buses` buses each deliver one bus word per cycle: one 32-bit value (scalar), or a
//   2x2 quad of values at (x, y), (x+1, y), (x, y+1), (x+1, y+1) (the line FIFO banked by
//   row and column parity can read any 2x2 window at once).
// - TripleMAC t forms the three responses of block determinant t (filter_geometry.h): it
//   snoops every bus, takes at most one value per cycle, and a coefficient of +-3 keeps it
//   busy `x3_cycles` cycles (three additions; it does not report busy, so the sequence
//   must never hand it a value then).
// - Without reuse each determinant's 32 reads are delivered for it alone (a quad word serves
//   the four pixels' determinants of one size at once). With reuse one delivered word is
//   taken by every free TripleMAC that needs a value in it.
// The generator is a greedy list scheduler: each cycle each bus carries the word whose free
// consumers have the most work left. Its length is compared with a lower bound (the busiest
// TripleMAC's work, or the words the buses must carry); the paper's basic script was ~11 %
// above optimal.
#include <array>
#include <string>
#include <vector>

#include "filter_geometry.h"

namespace surfvp::fhg {

enum class BusWord { scalar, quad };

struct SequenceParams {
    unsigned read_buses = 4;
    unsigned triple_macs = 18;
    unsigned fifo_lines = 56;
    unsigned x3_cycles = 3;
    BusWord bus_word = BusWord::quad;
    bool reuse = true;
    unsigned attempts = 16;  // greedy passes with different tie-breaks; the shortest is kept
};

struct Tap {
    int triple_mac;
    int lane;         // quad lane 0..3 = 2 ly + lx (0 for scalar words)
    int coefficient;  // +1, -1, +3, -3
    Response response;
};

struct Step {
    int cycle;
    int bus;
    int x, y;  // the word's (top-left) integral point, relative to the block's pixel (0, 0)
    std::vector<Tap> taps;
};

struct Sequence {
    std::vector<Step> steps;  // sorted by cycle, then bus
    int cycles = 0;           // until the last TripleMAC has finished its last addition
    int optimal_cycles = 0;   // lower bound
    int reads_per_block = 0;  // values the TripleMACs take: 18 x 32
    int distinct_reads_per_block = 0;  // distinct integral points among them
    int words_delivered = 0;           // bus words issued
    double overhead() const { return optimal_cycles ? double(cycles) / optimal_cycles - 1 : 0; }
};

// Throws std::invalid_argument for a configuration that cannot work, naming the parameter.
Sequence generate_sequence(const SequenceParams& params);

// Replays a sequence: every TripleMAC gets exactly the reads its determinant needs, with the
// right coefficient and response, at most one per cycle and never while busy. Returns ""
// when it holds, otherwise the first violation in words.
std::string check_sequence(const Sequence& sequence, const SequenceParams& params);

}  // namespace surfvp::fhg
