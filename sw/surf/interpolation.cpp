#include "sw/surf/interpolation.h"

#include <cmath>

#include <Eigen/Dense>

namespace surfvp::surf {

std::optional<Keypoint> interpolate_maximum(const ResponseStack& stack, const LocalMaximum& m, float max_offset) {
    const ResponseOctave& oct = stack.octaves[static_cast<size_t>(m.octave)];
    // r(dx, dy, ds): determinant at a neighbour, in double for the finite differences.
    auto r = [&](int dx, int dy, int ds) { return static_cast<double>(oct.at(m.layer + ds, m.kx + dx, m.ky + dy)); };
    const double v = r(0, 0, 0);
    const Eigen::Vector3d g{(r(1, 0, 0) - r(-1, 0, 0)) / 2, (r(0, 1, 0) - r(0, -1, 0)) / 2,
                            (r(0, 0, 1) - r(0, 0, -1)) / 2};
    const double dxx = r(1, 0, 0) + r(-1, 0, 0) - 2 * v;
    const double dyy = r(0, 1, 0) + r(0, -1, 0) - 2 * v;
    const double dss = r(0, 0, 1) + r(0, 0, -1) - 2 * v;
    const double dxy = (r(1, 1, 0) - r(-1, 1, 0) - r(1, -1, 0) + r(-1, -1, 0)) / 4;
    const double dxs = (r(1, 0, 1) - r(-1, 0, 1) - r(1, 0, -1) + r(-1, 0, -1)) / 4;
    const double dys = (r(0, 1, 1) - r(0, -1, 1) - r(0, 1, -1) + r(0, -1, -1)) / 4;
    Eigen::Matrix3d h;
    h << dxx, dxy, dxs, dxy, dyy, dys, dxs, dys, dss;

    Eigen::Matrix3d h_inv;
    bool invertible = false;
    h.computeInverseWithCheck(h_inv, invertible);
    if (!invertible) return std::nullopt;
    const Eigen::Vector3d offset = -h_inv * g;  // eq. 5
    if (!offset.allFinite() || offset.cwiseAbs().maxCoeff() > max_offset) return std::nullopt;

    const int layer_size = oct.layers[static_cast<size_t>(m.layer)].filter_size;
    const double size = layer_size + offset.z() * filter_spacing(m.octave);
    Keypoint kp;
    kp.x = static_cast<float>((m.kx + offset.x()) * oct.step);
    kp.y = static_cast<float>((m.ky + offset.y()) * oct.step);
    kp.scale = filter_scale(static_cast<float>(size));
    kp.response = m.response;
    return kp;
}

}  // namespace surfvp::surf
