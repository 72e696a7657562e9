#pragma once
// Parameters of the float reference SURF (see README.md for units and defaults).
namespace surfvp::surf {

// How orientation and descriptor evaluate their Haar wavelets (haar.h, README.md "Haar modes").
//   exact:   exact area integrals at real positions and sizes (bilinear reads, 8 corners x 4
//            values), the reference's own;
//   rounded: the embedded/OpenSURF way: the wavelet centred on the pixel corner nearest the
//            sample, integer half-size (round(s) for the descriptor, round(2s) for the
//            orientation), two integer boxes (8 distinct reads for dx and dy together),
//            integer sums, one int->float conversion per response.
enum class HaarMode { exact, rounded };
inline const char* haar_name(HaarMode mode) { return mode == HaarMode::exact ? "exact" : "rounded"; }

// The descriptor's sampling (descriptor.h): surf, Bay et al.'s 4 x 4 sub-regions of 5 x 5
// samples under one Gaussian; msurf, Agrawal et al.'s modified SURF (OpenSURF's default):
// sub-regions of 9 x 9 samples overlapping their neighbours by 2, each under its own Gaussian,
// and a second Gaussian over the sub-regions.
enum class DescriptorKind { surf, msurf };

// The defaults are the best CPU SURF measured here (docs/quality.md, "The float reference against
// the best CPU SURF"): OpenCV's 5 filter sizes per octave and interpolation limit of 1, OpenSURF's
// M-SURF descriptor. paper_surf() gives the paper's algorithm (§II), which the chip computes.
struct Params {
    // Hessian-determinant threshold: the determinant of box responses normalised by the filter
    // area L^2 on an image with values 0..255, i.e. OpenSURF's 0..1 units times 255^2 (OpenSURF's
    // 0.0004 is 26 here). OpenCV's `hessianThreshold` normalises each box by its own area and is
    // ~20-25 times larger for the same points (fast_hessian.h, README.md). Default: OpenSURF's.
    float threshold = 26.0f;
    int octaves = 4;                  // 1..4; octave o (0-based) uses sampling step init_step * 2^o
    int intervals = 5;                // filter sizes per octave, 3..8 (the paper and the chip: 4; OpenCV: 5)
    int init_step = 1;                // sampling step of octave 0, 1 or 2 (the chip uses 1, OpenSURF 2)
    bool upright = false;             // U-SURF: orientation 0, no orientation assignment
    HaarMode haar = HaarMode::exact;  // Haar wavelets of orientation and descriptor
    DescriptorKind descriptor = DescriptorKind::msurf;
    // The interpolation drops a maximum whose fitted |offset| exceeds this, in samples (x, y)
    // or intervals: 0.5 is the paper's rule, 1 OpenCV's.
    float max_offset = 1.0f;
    // One keypoint per blob (twins.h): of two maxima that interpolate to the same blob, keep the
    // stronger. Off only for the chip's software in float, which keeps what the chip keeps.
    bool one_per_blob = true;
    int threads = 0;  // 0: all hardware threads
};

// The paper's SURF (§II, after Bay et al. 2008): 4 filter sizes per octave, maxima dropped
// beyond half a sample, Bay's descriptor; 4 octaves and exact Haar wavelets. With octaves = 2
// and haar = rounded it is the chip's software in float.
inline Params paper_surf() {
    Params p;
    p.intervals = 4;
    p.max_offset = 0.5f;
    p.descriptor = DescriptorKind::surf;
    return p;
}

}  // namespace surfvp::surf
