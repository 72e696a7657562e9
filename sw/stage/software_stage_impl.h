#pragma once
// BasicSoftwareStage's members, for each meter's instantiation: software_stage.cpp (the
// platform's CostCounter) and sw/cpu_cost/firmware (the PPC440 build, a marking meter).
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "models/common/byte_order.h"
#include "models/fhg/fhg_regs.h"
#include "models/fhg/filter_geometry.h"
#include "models/fhg/hessian_core.h"
#include "models/fhg/local_max_finder.h"
#include "sw/stage/software_stage.h"
#include "sw/surf/descriptor.h"
#include "sw/surf/interpolation.h"
#include "sw/surf/memory_view.h"
#include "sw/surf/orientation.h"

namespace surfvp::sw {
namespace stage_detail {

// The scales of the two octaves the FHG covers, as indices into fhg::kSizes
// (9, 15, 21, 27, 39, 51): octave 1 is 9..27 at step 1, octave 2 is 15, 27, 39, 51 at step 2
// (paper Table I; docs/sources.md#surf).
constexpr int kOctaveSizes[2][4] = {{0, 1, 2, 3}, {1, 3, 4, 5}};
// Octave 2's four scales in the block record of an even pixel (fhg_regs.h): its 15 and 27 are
// octave 1's values there (k = 4 i + 0 for i = 1, 3), 39 and 51 are k = 16 and 17.
constexpr int kOctave2Record[4] = {4, 12, 16, 17};

// Every integral-image read of orientation, descriptor and hessian_at, with its bus address.
template <class Meter>
struct IntegralProbe {
    Meter* meter;
    void load(uint32_t address, unsigned bytes) const { meter->load(Read::integral, address, bytes); }
};

void check_frame(const FrameBuffers& f) {
    if (!f.integral || !f.determinants || f.width <= 0 || f.height <= 0 ||
        (f.det_bytes != 1 && f.det_bytes != 2 && f.det_bytes != 4) ||
        f.integral_stride < static_cast<size_t>(f.width) * 4)
        throw std::invalid_argument("software stage: frame buffers missing or smaller than the image");
}

}  // namespace stage_detail

template <class Meter>
struct BasicSoftwareStage<Meter>::Scan {
    int x = 0, y = 0;  // candidate pixel
    int octave = 0;    // 0: octave 1, 1: octave 2 (sw/surf's 0-based numbering)
    int layer = 0;     // 1 or 2: its scale within the octave's four
    int step = 1;      // pixels between samples: 1, 2

    int size(int layer_index) const { return fhg::kSizes[stage_detail::kOctaveSizes[octave][layer_index]]; }
    // Byte offset in the determinant buffer of scale `layer_index` at pixel (px, py).
    size_t offset(int px, int py, int layer_index, int width, unsigned det_bytes) const {
        const size_t blocks_per_row = static_cast<size_t>(width + 1) / 2;
        const size_t record = static_cast<size_t>(py / 2) * blocks_per_row + static_cast<size_t>(px / 2);
        const int k = octave == 0 ? 4 * layer_index + 2 * (py % 2) + px % 2 : stage_detail::kOctave2Record[layer_index];
        return record * fhg_regs::record_bytes(det_bytes) + static_cast<size_t>(k) * det_bytes;
    }
};

template <class Meter>
BasicSoftwareStage<Meter>::BasicSoftwareStage(const StageParams& params, Meter meter)
    : params_(params), meter_(std::move(meter)) {
    if (params.haar != surf::HaarMode::exact && params.haar != surf::HaarMode::rounded)
        throw std::invalid_argument("software stage: haar mode must be exact or rounded");
    if (params.descriptor != surf::DescriptorKind::surf && params.descriptor != surf::DescriptorKind::msurf)
        throw std::invalid_argument("software stage: descriptor must be surf or msurf");
    stack_.octaves.resize(2);
    for (int o = 0; o < 2; ++o) {
        surf::ResponseOctave& oct = stack_.octaves[static_cast<size_t>(o)];
        oct.octave = o;
        oct.step = 1 << o;
        oct.cols = oct.rows = 3;
        oct.layers.resize(3);
        for (surf::ResponseLayer& layer : oct.layers) layer.det.assign(9, 0.0f);
    }
}

template <class Meter>
void BasicSoftwareStage<Meter>::begin_frame() {
    meter_.begin_frame();
}

template <class Meter>
std::optional<surf::Keypoint> BasicSoftwareStage<Meter>::process(uint32_t fifo_word, const FrameBuffers& frame) {
    stage_detail::check_frame(frame);
    const fhg::Candidate c = fhg::unpack_candidate(fifo_word);
    const bool octave2 = (fifo_word >> 27) & 1;
    if (!(fifo_word >> 31) || c.size_index < 1 || c.size_index > 4 || octave2 != (c.octave() == 2))
        throw std::invalid_argument("software stage: not a candidate word: " + std::to_string(fifo_word));

    meter_.enter(Step::check);
    ++stats_.candidates;
    meter_.count(Unit::candidate, 1);
    Scan scan;
    scan.x = c.x;
    scan.y = c.y;
    scan.octave = c.octave() - 1;
    scan.layer = scan.octave == 0 ? c.size_index : c.size_index - 2;  // 15, 21 -> 1, 2; 27, 39 -> 1, 2
    scan.step = 1 << scan.octave;

    std::optional<surf::Keypoint> kp;
    Cube values{};
    if (!inside(scan, frame)) {
        ++stats_.rejected_border;
    } else if (!is_maximum(scan, frame, values)) {
        ++stats_.rejected_not_maximum;
    } else {
        meter_.enter(Step::interpolation);
        kp = interpolate(scan, values, frame.det_frac_bits);
        if (!kp) {
            ++stats_.rejected_interpolation;
        } else {
            describe(scan, frame, *kp);
            ++stats_.keypoints;
        }
    }
    meter_.leave();
    return kp;
}

// All 27 samples inside the image, and every filter fits there: the FHG writes 0 where a
// filter does not fit (hessian_core.h), which is no response to compare with. Equivalent to
// sw/surf's rule that the whole 3x3x3 neighbourhood exists (local_maxima.h), with the FHG's
// border (b <= x <= width - 1 - b) instead of the reference's one pixel more.
template <class Meter>
bool BasicSoftwareStage<Meter>::inside(const Scan& s, const FrameBuffers& f) const {
    for (int l = s.layer - 1; l <= s.layer + 1; ++l)
        for (int d : {-s.step, s.step})
            if (!fhg::HessianCore::inside(f.width, f.height, s.x + d, s.y + d, s.size(l))) return false;
    return true;
}

// Above the threshold and strictly above all 26 neighbours (ties are no maximum), in the
// FHG's fixed point: the same rule as sw/surf's find_local_maxima. The centre first, then its
// own scale (which rejects most), then the scales below and above; stops at the first loss,
// as the code on the CPU would.
template <class Meter>
bool BasicSoftwareStage<Meter>::is_maximum(const Scan& s, const FrameBuffers& f, Cube& values) {
    auto load = [&](int dx, int dy, int dl) {
        const size_t offset = s.offset(s.x + dx * s.step, s.y + dy * s.step, s.layer + dl, f.width, f.det_bytes);
        meter_.load(Read::determinant, f.determinants_address + static_cast<uint32_t>(offset), f.det_bytes);
        meter_.count(Unit::compare, 1);
        return values[dl + 1][dy + 1][dx + 1] = fhg_regs::load_det(f.determinants + offset, f.det_bytes);
    };
    // v > threshold <=> v > floor(threshold x 2^F) for an integer v; or the FHG's own register.
    meter_.count(Unit::scan, 1);
    const double threshold = register_threshold_
                                 ? double(*register_threshold_)
                                 : std::floor(std::ldexp(static_cast<double>(params_.threshold), int(f.det_frac_bits)));
    const int32_t centre = load(0, 0, 0);
    if (!(centre > threshold)) {
        ++stats_.inconsistent;
        return false;
    }
    for (int dl : {0, -1, 1})
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if ((dl || dy || dx) && !(centre > load(dx, dy, dl))) return false;
    return true;
}

// sw/surf's interpolate_maximum() on a 3x3x3 stack holding the 27 values: the same fit and
// the paper's rule (reject any |offset| > 0.5). Its sample (1, 1) is the candidate, so its x
// (1 + o_x) step becomes x + o_x step here. Scale 1.2 (L + o_s dL) / 9, dL = 6 (octave 1) or
// 12 (octave 2); response = the candidate's own determinant, as in the reference.
template <class Meter>
std::optional<surf::Keypoint> BasicSoftwareStage<Meter>::interpolate(const Scan& s, const Cube& values,
                                                                     unsigned det_frac_bits) {
    meter_.count(Unit::solve, 1);
    surf::ResponseOctave& oct = stack_.octaves[static_cast<size_t>(s.octave)];
    const float unit = std::ldexp(1.0f, -int(det_frac_bits));
    for (int l = 0; l < 3; ++l) {
        surf::ResponseLayer& layer = oct.layers[static_cast<size_t>(l)];
        layer.filter_size = s.size(s.layer - 1 + l);
        for (int dy = 0; dy < 3; ++dy)
            for (int dx = 0; dx < 3; ++dx)
                layer.det[static_cast<size_t>(dy * 3 + dx)] = static_cast<float>(values[l][dy][dx]) * unit;
    }
    surf::LocalMaximum m;
    m.octave = s.octave;
    m.layer = 1;
    m.kx = m.ky = 1;
    m.response = oct.at(1, 1, 1);
    std::optional<surf::Keypoint> kp = surf::interpolate_maximum(stack_, m, params_.max_offset);
    if (!kp) return std::nullopt;
    meter_.count(Unit::keypoint, 1);
    kp->x += static_cast<float>(s.x - s.step);
    kp->y += static_cast<float>(s.y - s.step);
    return kp;
}

// Laplacian, orientation and descriptor from the integral image in DDR, through the reference
// code on a MemoryView; each read is counted and goes through the cache model.
template <class Meter>
void BasicSoftwareStage<Meter>::describe(const Scan& s, const FrameBuffers& f, surf::Keypoint& kp) {
    const surf::MemoryView<stage_detail::IntegralProbe<Meter>> view{
        f.integral, f.integral_address, f.width,
        f.height,   f.integral_stride,  stage_detail::IntegralProbe<Meter>{&meter_}};
    meter_.enter(Step::laplacian);
    meter_.count(Unit::laplacian, 1);
    kp.laplacian = surf::hessian_at(view, s.x, s.y, s.size(s.layer)).laplacian;

    if (!params_.upright) {
        meter_.enter(Step::orientation);
        meter_.count(Unit::orientation, 1);
        int angles = 0;
        kp.orientation = surf::orientation(view, kp.x, kp.y, kp.scale, params_.haar, &angles);
        meter_.count(Unit::angle, uint64_t(angles));
    } else {
        kp.orientation = 0;
    }

    meter_.enter(Step::descriptor);
    const bool msurf = params_.descriptor == surf::DescriptorKind::msurf;
    meter_.count(msurf ? Unit::msurf : Unit::descriptor, 1);
    kp.descriptor = surf::descriptor(view, kp, params_.haar, params_.descriptor);
}

}  // namespace surfvp::sw
