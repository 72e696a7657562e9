#pragma once
// The PPC440's part of FPGA-SURF (paper §III-D, phase 4; DESIGN "the data's way", step 4): for
// each candidate the FHG pushed into its maxima FIFO, the CPU re-checks all 26 neighbours in
// the determinant buffer (LocMaxFinder only compared two blocks, paper §III-C), interpolates
// position and scale (eqs. 4-5), and builds the Laplacian sign, orientation and SURF-64
// descriptor from the integral image in DDR, reusing the float reference's code (sw/surf)
// through a MemoryView. Every step tells a meter what it did (sw/cpu_cost/work_units.h): on the
// platform a CostCounter, which the driver turns into CPU time; in the PPC440 build of the same
// code (sw/cpu_cost/firmware) a meter that only marks the steps for the instruction trace.
// Plain C++: no SystemC, no HAL (the caller maps the buffers).
#include <cstddef>
#include <cstdint>
#include <optional>

#include "sw/cpu_cost/cost_model.h"
#include "sw/cpu_cost/work_units.h"
#include "sw/surf/fast_hessian.h"
#include "sw/surf/keypoint.h"
#include "sw/surf/params.h"

namespace surfvp::sw {

// Where the hardware left one frame, as the CPU sees memory (big-endian, byte_order.h).
struct FrameBuffers {
    const uint8_t* integral = nullptr;      // IIG output: 32-bit words, row-major
    uint32_t integral_address = 0;          // bus address of integral[0]
    size_t integral_stride = 0;             // bytes from one row to the next
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
    float threshold = 0;  // determinant threshold in float units (sw/surf/README.md)
    // The interpolation drops a maximum whose |offset| exceeds this (samples): 0.5 is the
    // paper's rule (§II), 1 OpenCV's (sw/surf/params.h).
    float max_offset = 0.5f;
    // The descriptor's sampling (sw/surf/params.h): Bay's (the paper's) or M-SURF's; each its
    // own unit of work (work_units.h), priced by the calibration.
    surf::DescriptorKind descriptor = surf::DescriptorKind::surf;
};

// Meter: void enter(Step), void leave() (the candidate is done), void count(Unit, uint64_t),
// void load(Read, uint32_t address, unsigned bytes), void begin_frame() (work_units.h).
template <class Meter>
class BasicSoftwareStage {
public:
    // Throws std::invalid_argument for a Haar mode other than exact or rounded, or a descriptor
    // kind other than surf or msurf.
    explicit BasicSoftwareStage(const StageParams& params, Meter meter = Meter());

    // One maxima-FIFO word -> a keypoint (position, scale, response = the candidate's own
    // determinant, Laplacian, orientation, descriptor), or nothing when the candidate touches
    // the border, is not above the threshold and all 26 neighbours, or the interpolation
    // rejects it. Tells the meter its work. Throws std::invalid_argument for a word
    // without the valid bit or with a size index the FHG never sends, or for empty buffers.
    std::optional<surf::Keypoint> process(uint32_t fifo_word, const FrameBuffers& frame);

    // A new frame's buffers were written by DMA: drop the cached lines (the PPC440's L1 is
    // not coherent with DMA; the cost of the invalidation itself is the driver's).
    void begin_frame();

    // The FHG's THRESHOLD register for the frames from now on (fixed point, in the
    // determinants' format): a candidate's own determinant must be above it, as the FHG
    // compared it (the driver's keypoint-count control gives each frame its own). Until it is
    // given, params.threshold in float units.
    void set_register_threshold(int32_t threshold) { register_threshold_ = threshold; }

    Meter& cost() { return meter_; }  // the driver calls cost().take_cycles() and consume()s them
    const Meter& cost() const { return meter_; }

    struct Stats {
        uint64_t candidates = 0, rejected_not_maximum = 0, rejected_interpolation = 0, rejected_border = 0,
                 keypoints = 0;
        // Candidates whose own determinant in memory is not above the threshold, although the
        // FHG marks only those above it: the determinant buffer does not hold what the FHG
        // computed (counted among rejected_not_maximum too).
        uint64_t inconsistent = 0;
    };
    const Stats& stats() const { return stats_; }

private:
    struct Scan;                    // one decoded candidate and its neighbourhood's geometry
    using Cube = int32_t[3][3][3];  // determinants [scale][dy][dx], fixed point

    bool inside(const Scan& scan, const FrameBuffers& frame) const;
    bool is_maximum(const Scan& scan, const FrameBuffers& frame, Cube& values);
    std::optional<surf::Keypoint> interpolate(const Scan& scan, const Cube& values, unsigned det_frac_bits);
    void describe(const Scan& scan, const FrameBuffers& frame, surf::Keypoint& kp);

    StageParams params_;
    std::optional<int32_t> register_threshold_;
    Meter meter_;
    Stats stats_;
    surf::ResponseStack stack_;  // a 3x3x3 stack: how sw/surf's interpolation takes the values
};

// The platform's stage: priced by the calibrated cost model (software_stage.cpp instantiates it;
// the member definitions are in software_stage_impl.h for the firmware's own instantiation).
using SoftwareStage = BasicSoftwareStage<CostCounter>;
extern template class BasicSoftwareStage<CostCounter>;

}  // namespace surfvp::sw
