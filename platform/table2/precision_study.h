#pragma once
// `surfvp precision SCENARIO [--pair SCENARIO]`: how many bits the FHG needs. Each of the
// FHG's arithmetic widths (and the IIG's integral bits, and the software's Haar mode) is
// narrowed alone from the scenario's values; every point runs the chip (direct mode) on the
// sequence and measures the four rows of Table II on consecutive frames, and on the pair
// (a homography scenario) repeatability and precision, with what the width costs: RAMB36,
// DSP48E, LUTs and the determinant bytes each frame writes over PLB2. Against full precision
// (the same algorithm in float: the float reference with the chip's software settings), the
// report names the fewest bits of each width that keep every row within 0.01, and checks them
// all together in one more point. Points run as forked children (the sweep's engine).
// docs/precision.md is the user's description.
#include <string>
#include <vector>

namespace surfvp {

struct PrecisionOptions {
    std::string scenario;           // a sequence (Table II rows)
    std::string pair;               // a homography pair (repeatability, precision); empty: none
    std::vector<std::string> sets;  // the sequence's (the pair takes only each point's widths)
    std::vector<std::string> axes;  // KEY=V1,V2,...; empty: the built-in widths (docs/precision.md)
    std::string out;                // default: traces/precision_<scenario name>
    unsigned jobs = 0;              // 0: one per core
    bool quiet = false;
};

// Exit codes: 0 written, 1 some point could not run (its error is in the report), 2 bad
// input, 3 internal error, 4 a file could not be written.
int precision_command(const PrecisionOptions& options);

}  // namespace surfvp
