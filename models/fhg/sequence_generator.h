#pragma once
// The MasterController's "control and addressing sequence" (paper §III-C, Fig. 6, note 4):
// the order in which the read buses deliver integral-image values of one 2x2 determinant
// block to the TripleMACs, generated here from the filter geometry instead of being taken
// as a number. Plain C++.
//
// The machine it schedules:
// - `read_buses` buses each deliver one bus word per cycle: one 32-bit value (scalar), two
//   neighbours on one line (pair: (x, y), (x+1, y)), or a 2x2 quad ((x, y), (x+1, y),
//   (x, y+1), (x+1, y+1)).
// - The line FIFO holds each integral line in block RAM, organised as `line_fifo` says
//   (LineFifo below): how many BRAMs a line is spread over, how many reads each serves in an
//   FHG cycle, and whether a read returns one value or an aligned pair. A word reads only the
//   values some TripleMAC takes from it (an octave-2 word carrying one value reads one), each
//   through the BRAM port its lane is wired to (lane_port below), and a port reads one
//   address a cycle.
// - TripleMAC t forms the three responses of block determinant t (filter_geometry.h): it
//   snoops every bus, takes at most one value per cycle, and a coefficient of +-3 keeps it
//   busy `x3_cycles` cycles (three additions; it does not report busy, so the sequence
//   must never hand it a value then).
// - Without reuse each value a determinant needs is delivered for it alone (a quad or pair
//   word serves the same read of the neighbouring pixels' determinants of one size at
//   once). With reuse one delivered word is taken by every free TripleMAC that needs a value
//   in it.
// - Blocks follow each other without a gap: the sequence runs again `interval` cycles after
//   it started. The end-of-sequence signal makes each TripleMAC latch its result into its
//   output buffer once its last addition is done (paper §III-C), so a x3 still being added
//   overlaps the next block's first cycles; a TripleMAC's first value of the next block must
//   come after its last addition of this one. HessianCalc reads the output buffers while the
//   next block accumulates (Fhg::block_cycles takes the longer of the two).
//
// Two schedulers, both list schedulers that fill cycle after cycle (each bus carries the
// word whose free consumers have the most work left; ties are broken by a seeded draw):
// - `basic`, the paper's "very basic algorithm" (§III-C) as we reconstruct it: one such pass,
//   no reuse, nothing else. Its ties are arbitrary, so one pass is a draw: the sequence used
//   is the median of `attempts` passes, and their spread is reported.
// - `improved`, a what-if "better script": the same pass also weighing how much each BRAM it
//   reads still has to serve, with reuse where the machine allows it; the best of `attempts`.
// Both are compared with a lower bound under the same limits: the busiest TripleMAC's work,
// the words the buses must carry, or the reads the busiest BRAM must serve.
#include <array>
#include <string>
#include <vector>

#include "filter_geometry.h"

namespace surfvp::fhg {

enum class BusWord { scalar, pair, quad };
enum class Scheduler { basic, improved };

// How a line of the line FIFO is held in Virtex-5 block RAM (UG190: a RAMB36 has two ports of
// at most 36 bit in true dual-port mode, or one 72-bit read port and one write port in simple
// dual-port mode). Writes of incoming lines go to lines outside the 52-line window, so every
// port of a line in the window is free for the read buses.
enum class LineFifo {
    tdp,     // one RAMB36 (1K x 32) per line, true dual-port at the FHG clock: 2 reads a cycle
    tdp_x2,  // one RAMB36 per line, true dual-port, clocked at twice the FHG clock: 4 reads a cycle
    banked,  // two RAMB36 per line, columns interleaved (x mod 2), each true dual-port: 2 reads each
    sdp72,   // one RAMB36 per line, simple dual-port 512 x 72: one read of an aligned pair (2k, 2k+1)
};
struct LineFifoShape {
    int banks;           // BRAMs a line is spread over, by column (x mod banks)
    int reads;           // reads one of them serves per FHG cycle
    bool aligned_pairs;  // a read returns the aligned pair holding the value (SDP 72 bit)
    int clock_multiple;  // the BRAMs' clock as a multiple of the FHG's
};
LineFifoShape line_fifo_shape(LineFifo fifo);
const char* line_fifo_name(LineFifo fifo);

// One BRAM of a line FIFO whose lines hold `line_words` values: its words (a value each, or an
// aligned pair; a bank holds every banks-th column) and the bits that address them (at least 1).
struct LineBram {
    unsigned words = 0, address_bits = 1;
};
LineBram line_bram(LineFifo fifo, unsigned line_words);

struct SequenceParams {
    unsigned read_buses = 4;
    unsigned triple_macs = 18;
    unsigned fifo_lines = 56;
    unsigned x3_cycles = 3;
    BusWord bus_word = BusWord::quad;
    bool reuse = true;
    LineFifo line_fifo = LineFifo::tdp_x2;
    // Which lines a bus lane reaches (line_group below): 1, every line (a full crossbar); 2 or
    // 4, the lines of one group of slots, so a lane's multiplexer spans 1/line_groups of the BRAMs.
    unsigned line_groups = 2;
    Scheduler scheduler = Scheduler::basic;
    unsigned attempts = 16;  // passes with different tie-breaks: basic takes their median, improved the shortest
};

struct Tap {
    int triple_mac;
    int lane;         // the value's position in the word: scalar 0; pair 0, 1 (x, x+1); quad 2 ly + lx
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
    std::vector<Step> steps;    // sorted by cycle, then bus
    int interval = 0;           // cycles per block in the steady state: when the sequence starts again
    int span = 0;               // from its first cycle until the last TripleMAC's last addition
    int optimal_cycles = 0;     // lower bound on the interval under the same limits (the structural bound)
    std::string optimal_limit;  // what sets that bound (every limit that reaches it)
    // The paper's "optimal state" (its note 4): the read buses never idle waiting for a busy
    // TripleMAC, i.e. every bus carries one of this sequence's words every cycle.
    int busy_bus_cycles = 0;
    std::array<int, 2> spread{};       // basic: the shortest and longest interval of its passes
    int reads_per_block = 0;           // values the TripleMACs take: 18 x 32
    int distinct_reads_per_block = 0;  // distinct integral points among them
    int words_delivered = 0;           // bus words issued
    // Over the structural bound (ports, buses, TripleMAC work).
    double overhead() const { return optimal_cycles ? double(interval) / optimal_cycles - 1 : 0; }
    // Over the paper's optimal state: idle bus cycles only, against the words it carries.
    double idle_bus_overhead() const { return busy_bus_cycles ? double(interval) / busy_bus_cycles - 1 : 0; }
};

// With params.scheduler. Throws std::invalid_argument for a configuration that cannot work,
// naming the parameter.
Sequence generate_sequence(const SequenceParams& params);

// What reading the value at (y, x) of the block's window takes from the line FIFO: one read of
// `unit` (its column, or with 72-bit reads its aligned pair) on BRAM `bram` (the window line's,
// and its column bank's). A BRAM serves line_fifo_shape().reads distinct units a cycle.
struct LineRead {
    int bram;
    int unit;
};
LineRead line_read(const SequenceParams& params, int y, int x);

// The read port of a BRAM that lane `lane` of bus `bus` reads through: fixed wiring, not a
// choice of the sequence. Letting any lane reach any port costs more LUTs than the FX70T has
// (docs/rtl.md); with one port a lane, a lane's value comes through a (lines x banks):1
// multiplexer and a port's address from the few lanes wired to it. The ports are dealt out
// column by column, bus after bus ((bus x the word's columns + the lane's column) mod reads),
// so the two columns of a word take two ports, and neighbouring buses different ones.
// A port reads one unit a cycle: lanes wired to it share it only if they want that unit.
int lane_port(const SequenceParams& params, int bus, int lane);

// The line groups: the line FIFO's slots are dealt into `line_groups` groups (slot mod
// line_groups), and each bus lane is wired to the BRAMs of one group only: lane (dy) of bus b
// to group (b + dy) mod line_groups. The sequence addresses window lines (line 0 is the block's
// pixel row - 26), and the window's top slot steps by two lines a block row, so at a window
// whose top slot is in group 0 a word whose top line is window line L goes on a bus of group L
// mod line_groups; the line FIFO rotates its buses by (top slot mod line_groups) at the other
// windows (only with 4 groups: 0 or 2), which keeps every lane in its group with one sequence.
// So a bus reaches 1/line_groups of the window's lines; it needs read_buses to be a multiple
// of line_groups, and line_groups to divide the FIFO's lines. A quad word that carries values
// of one line only (octave 2's) may sit a line higher, the values in its lower lanes, so that a
// bus of the other group can carry it.
int line_group(const SequenceParams& params, int y);             // the group of the window line at block row y
bool bus_reaches(const SequenceParams& params, int bus, int y);  // whether a word at top line y may go on bus

// Values of a bus word, as (dy, dx) offsets from its top-left point, in lane order.
const std::vector<std::array<int, 2>>& word_shape(BusWord word);
const char* bus_word_name(BusWord word);
const char* scheduler_name(Scheduler scheduler);

// Replays a sequence against every limit of the machine: each TripleMAC gets exactly the
// reads its determinant needs with the right coefficient and response, at most one value a
// cycle and never while busy, also across the step to the next block; one word per bus and
// cycle; each value a tap takes read through its lane's port (lane_port), and no port reading
// two units in a cycle; every word lies in the 52-line window. Returns "" when it holds, otherwise the first violation in words.
std::string check_sequence(const Sequence& sequence, const SequenceParams& params);

}  // namespace surfvp::fhg
