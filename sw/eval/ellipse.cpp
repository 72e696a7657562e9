#include "sw/eval/ellipse.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "sw/eval/homography.h"

namespace surfvp::eval {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Chord {
    double left = 0, right = 0;
    bool empty = true;
};

// The ellipse's chord on the horizontal line y = row: a u^2 + 2 b v u + c v^2 <= 1 with
// u = x - cx, v = row - cy.
Chord chord(const Ellipse& e, double row) {
    double a = e.m(0, 0), b = e.m(0, 1), c = e.m(1, 1);
    double v = row - e.centre.y();
    double discriminant = a - (a * c - b * b) * v * v;  // (b v)^2 - a (c v^2 - 1)
    if (discriminant <= 0) return {};
    double root = std::sqrt(discriminant);
    return {e.centre.x() + (-b * v - root) / a, e.centre.x() + (-b * v + root) / a, false};
}

}  // namespace

Ellipse Ellipse::circle(const Eigen::Vector2d& centre, double radius) {
    return {centre, Eigen::Matrix2d::Identity() / (radius * radius)};
}

double Ellipse::area() const { return kPi / std::sqrt(m.determinant()); }

double Ellipse::equivalent_radius() const { return std::pow(m.determinant(), -0.25); }

Eigen::Vector2d Ellipse::half_extent() const {
    // The extent along x is sqrt of (m^-1)_00 = c / det, along y sqrt(a / det).
    double det = m.determinant();
    return {std::sqrt(m(1, 1) / det), std::sqrt(m(0, 0) / det)};
}

Ellipse Ellipse::scaled(double factor) const { return {centre, m / (factor * factor)}; }

Ellipse map_ellipse(const Ellipse& e, const Eigen::Vector2d& new_centre, const Eigen::Matrix2d& a) {
    Eigen::Matrix2d inverse = a.inverse();
    Eigen::Matrix2d m = inverse.transpose() * e.m * inverse;
    return {new_centre, 0.5 * (m + m.transpose())};  // symmetric to the last bit
}

Ellipse map_ellipse(const Ellipse& e, const Eigen::Matrix3d& h) {
    return map_ellipse(e, apply_homography(h, e.centre), homography_jacobian(h, e.centre));
}

double ellipse_overlap(const Ellipse& a, const Ellipse& b, int rows) {
    if (rows < 1) throw std::invalid_argument("ellipse_overlap: rows must be positive");
    double top = std::max(a.centre.y() - a.half_extent().y(), b.centre.y() - b.half_extent().y());
    double bottom = std::min(a.centre.y() + a.half_extent().y(), b.centre.y() + b.half_extent().y());
    double intersection = 0;
    if (bottom > top) {
        double step = (bottom - top) / rows;
        for (int i = 0; i < rows; ++i) {
            double row = top + (i + 0.5) * step;
            Chord ca = chord(a, row), cb = chord(b, row);
            if (ca.empty || cb.empty) continue;
            intersection += std::max(0.0, std::min(ca.right, cb.right) - std::max(ca.left, cb.left));
        }
        intersection *= step;
    }
    double area_a = a.area(), area_b = b.area();
    intersection = std::min({intersection, area_a, area_b});
    return intersection / (area_a + area_b - intersection);
}

}  // namespace surfvp::eval
