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

struct Params {
    // Hessian-determinant threshold: the determinant of box responses normalised by the filter
    // area L^2 on an image with values 0..255, i.e. OpenSURF's 0..1 units times 255^2 (OpenSURF's
    // 0.0004 is 26 here). OpenCV's `hessianThreshold` normalises each box by its own area and is
    // ~20-25 times larger for the same points (fast_hessian.h, README.md). Default: OpenSURF's.
    float threshold = 26.0f;
    int octaves = 4;       // 1..4; octave o (0-based) uses sampling step init_step * 2^o
    int intervals = 4;     // filter sizes per octave, 3..8 (the paper and the chip use 4)
    int init_step = 1;     // sampling step of octave 0, 1 or 2 (the chip uses 1, OpenSURF 2)
    bool upright = false;  // U-SURF: orientation 0, no orientation assignment
    HaarMode haar = HaarMode::exact;  // Haar wavelets of orientation and descriptor
    int threads = 0;       // 0: all hardware threads
};

}  // namespace surfvp::surf
