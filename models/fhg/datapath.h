#pragma once
// Where an FHG's determinants come from when HessianCore does not give them (fhg.model): a
// whole datapath that takes the frame's integral lines and gives block rows, in order, with
// the cycles it spent on each. Plain C++: the Fhg module moves the data and spends the time.
#include <cstdint>
#include <vector>

#include "models/iig/integral_core.h"

namespace surfvp::fhg {

// fhg.model: HessianCore (the model) or the verilated Verilog reference (models/fhg/rtl).
enum class DatapathModel { core, rtl };

class Datapath {
public:
    struct Row {
        std::vector<int32_t> records;  // ceil(width / 2) blocks of 18 determinants (HessianCore::block's)
        uint64_t cycles = 0;           // the datapath's clock cycles on the row's sequence
    };
    virtual ~Datapath() = default;
    // A new frame; whatever the last one left is dropped.
    virtual void start(int width, int height) = 0;
    // Block row `by`, the next after the last one given, from the frame's first `received`
    // integral lines (all the row's window). Throws std::runtime_error if the datapath cannot
    // finish the row with them.
    virtual Row row(const IntegralView& frame, int received, int by) = 0;
};

}  // namespace surfvp::fhg
