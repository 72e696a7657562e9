#pragma once
// The Verilog reference of this folder, verilated, as an FHG datapath: the platform's
// fhg.model=rtl and the co-simulation's device under test. Verilator's headers stay in the
// .cpp (a verilated model's headers must not meet SystemC's), so this header is plain C++.
//
// The build verilates the RTL once, with the parameters of the model's defaults
// (fhg_params.vh): a configuration whose widths, constants or sequence layout differ cannot
// run on it, and rtl_build_difference names the first parameter that keeps them apart.
#include <memory>
#include <string>

#include "models/fhg/datapath.h"
#include "models/fhg/hessian_core.h"
#include "models/fhg/sequence_generator.h"
#include "models/fhg/sequence_memory.h"

namespace surfvp::fhg {

// "" when the verilated build is this configuration's; else the first parameter of
// fhg_params.vh that differs, as "RESPONSE_BITS = 16 here, 18 in the build".
std::string rtl_build_difference(const Precision& precision, const SequenceParams& sequence, unsigned line_words);

class RtlDatapath : public Datapath {
public:
    // The datapath with `image` in its sequence memory (the configuration's own, or any other of
    // its layout). Throws std::invalid_argument naming the difference if the build is not this
    // configuration's (rtl_build_difference).
    RtlDatapath(const Precision& precision, const SequenceParams& sequence, unsigned line_words,
                const SequenceImage& image);
    ~RtlDatapath() override;

    void start(int width, int height) override;
    Row row(const IntegralView& frame, int received, int by) override;

    // One clock cycle, the PixelBus offering the frame's next value while fewer than
    // `available` have been taken (row by row): the testbench's step. `det` is what HessianCalc
    // gives out after the edge.
    struct Determinant {
        bool valid = false;
        int block_x = 0, block_y = 0;  // the block (not its pixel)
        int index = 0;                 // record position 0..17
        int32_t value = 0;
    };
    Determinant step(const IntegralView& frame, size_t available);
    uint64_t cycles() const;  // since start
    bool overrun() const;     // a TripleMAC latched before HessianCalc had read the block before

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace surfvp::fhg
