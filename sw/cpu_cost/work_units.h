#pragma once
// What the software stage tells its meter, and nothing more: which step it is in, how many
// units of work it did, and which DDR words it read. The native cost model (cost_model.h)
// prices the units from the calibration table and replays the reads into the L1 model; the
// PPC440 build of the same code (firmware/) marks the step boundaries for the instruction
// trace and ignores the rest. No dependencies, so the cross-compiled firmware includes it too.
#include <cstddef>
#include <cstdint>

namespace surfvp::sw {

enum class Step : uint8_t { check, interpolation, laplacian, orientation, descriptor };
constexpr size_t kSteps = 5;

// A unit is work whose instruction stream does not depend on the data beyond a few percent
// (calibration.md shows the spread); each belongs to one step.
enum class Unit : uint8_t {
    candidate,    // check: decode one FIFO word, test the border
    scan,         // check: a candidate inside the border (the threshold in fixed point, the centre first)
    compare,      // check: one determinant loaded and compared
    solve,        // interpolation: the 3x3 fit of one maximum
    keypoint,     // interpolation: an accepted offset turned into position and scale
    laplacian,    // the Laplacian sign (hessian_at)
    orientation,  // one keypoint's orientation (109 samples, 36 windows)
    angle,        // orientation: a sample whose angle is computed (atan2; not where both responses are 0)
    descriptor,   // one keypoint's SURF-64 descriptor, Bay's (400 samples, normalisation)
    msurf,        // one keypoint's M-SURF descriptor instead (576 samples, 16 x 81 weights, normalisation)
};
constexpr size_t kUnits = 10;

enum class Read : uint8_t { integral, determinant };

constexpr Step step_of(Unit u) {
    switch (u) {
        case Unit::candidate:
        case Unit::scan:
        case Unit::compare:
            return Step::check;
        case Unit::solve:
        case Unit::keypoint:
            return Step::interpolation;
        case Unit::laplacian:
            return Step::laplacian;
        case Unit::orientation:
        case Unit::angle:
            return Step::orientation;
        case Unit::descriptor:
        case Unit::msurf:
            return Step::descriptor;
    }
    return Step::check;
}

const char* step_name(Step s);
const char* unit_name(Unit u);

// The keypoints among counted units: each has one descriptor of one kind.
template <class Counts>
uint64_t described_keypoints(const Counts& units) {
    return uint64_t(units[size_t(Unit::descriptor)]) + uint64_t(units[size_t(Unit::msurf)]);
}

}  // namespace surfvp::sw
