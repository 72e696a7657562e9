#pragma once
// The PPC440's part of FPGA-SURF (paper §III-D, phase 4; DESIGN "the data's way", step 4): for
// each candidate the FHG pushed into its maxima FIFO, the CPU re-checks all 26 neighbours in
// the determinant buffer (LocMaxFinder only compared two blocks, paper §III-C), interpolates
// position and scale (eqs. 4-5), and builds the Laplacian sign, orientation and SURF-64
// descriptor from the integral image in DDR, reusing the float reference's code (sw/surf)
// through a MemoryView. Every step counts its work into a CostCounter (sw/cpu_cost), which the
// driver turns into CPU time. Plain C++: no SystemC, no HAL (the caller maps the buffers).
#include <cstddef>
#include <cstdint>
#include <optional>

#include "sw/cpu_cost/cost_model.h"
#include "sw/surf/fast_hessian.h"
#include "sw/surf/keypoint.h"
#include "sw/surf/params.h"

namespace surfvp::sw {

// Where the hardware left one frame, as the CPU sees memory (big-endian, byte_order.h).
struct FrameBuffers {
    const uint8_t* integral = nullptr;  // IIG output: 32-bit words, row-major
    uint32_t integral_address = 0;      // bus address of integral[0]
    size_t integral_stride = 0;         // bytes from one row to the next
    const uint8_t* determinants = nullptr;  // FHG output: 72-byte block records (fhg_regs.h)
    uint32_t determinants_address = 0;      // bus address of determinants[0] (DET_ADDR)
    int width = 0, height = 0;              // pixels
    unsigned det_frac_bits = 0;             // FHG DET_FRAC_BITS
    unsigned det_bytes = 4;                 // FHG DET_BYTES: 1, 2 or 4 bytes per determinant
};

struct StageParams {
    bool upright = false;  // U-SURF: orientation 0, not computed
    // Haar wavelets of orientation and descriptor (sw/surf/params.h): exact area integrals at
    // real positions (the reference's), or rounded to whole pixels and sizes (OpenSURF-style,
    // integer sums). Charged by the mode in use (sw/cpu_cost/surf_op_counts.h).
    surf::HaarMode haar = surf::HaarMode::exact;
    float threshold = 0;   // determinant threshold in float units (sw/surf/README.md)
    CostParams cost;
};

class SoftwareStage {
public:
    explicit SoftwareStage(const StageParams& params);  // throws std::invalid_argument (cost params, haar)

    // One maxima-FIFO word -> a keypoint (position, scale, response = the candidate's own
    // determinant, Laplacian, orientation, descriptor), or nothing when the candidate touches
    // the border, is not above the threshold and all 26 neighbours, or the interpolation
    // rejects it. Counts its work into cost(). Throws std::invalid_argument for a word
    // without the valid bit or with a size index the FHG never sends, or for empty buffers.
    std::optional<surf::Keypoint> process(uint32_t fifo_word, const FrameBuffers& frame);

    // A new frame's buffers were written by DMA: drop the cached lines (the PPC440's L1 is
    // not coherent with DMA; the cost of the invalidation itself is the driver's).
    void begin_frame();

    CostCounter& cost() { return cost_; }  // the driver calls cost().take_cycles() and consume()s them
    const CostCounter& cost() const { return cost_; }

    struct Stats {
        uint64_t candidates = 0, rejected_not_maximum = 0, rejected_interpolation = 0, rejected_border = 0,
                 keypoints = 0;
    };
    const Stats& stats() const { return stats_; }

    // Cycles spent in each step so far (cost model, un-rounded); they add up to
    // cost().exact_cycles() while nothing else is counted into cost().
    struct PhaseCycles {
        double check = 0;          // decode, border, threshold and the 26 neighbours
        double interpolation = 0;  // the 3x3 solve and the keypoint's position and scale
        double laplacian = 0;
        double orientation = 0;
        double descriptor = 0;
    };
    const PhaseCycles& phase_cycles() const { return phases_; }

private:
    struct Scan;  // one decoded candidate and its neighbourhood's geometry
    using Cube = int32_t[3][3][3];  // determinants [scale][dy][dx], fixed point

    bool inside(const Scan& scan, const FrameBuffers& frame) const;
    bool is_maximum(const Scan& scan, const FrameBuffers& frame, Cube& values);
    std::optional<surf::Keypoint> interpolate(const Scan& scan, const Cube& values, unsigned det_frac_bits);
    void describe(const Scan& scan, const FrameBuffers& frame, surf::Keypoint& kp);
    void charge(double& phase, double& since);  // phase += cycles since `since`; since = now

    StageParams params_;
    CostCounter cost_;
    Stats stats_;
    PhaseCycles phases_;
    surf::ResponseStack stack_;  // a 3x3x3 stack: how sw/surf's interpolation takes the values
};

}  // namespace surfvp::sw
