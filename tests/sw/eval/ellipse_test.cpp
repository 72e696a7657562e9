// Ellipse geometry and the numerical overlap against closed forms.
#include "sw/eval/ellipse.h"

#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "sw/eval/homography.h"

namespace surfvp::eval {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Two circles of radius r whose centres are d apart: the lens area.
double equal_circles_overlap(double r, double d) {
    if (d >= 2 * r) return 0;
    double lens = 2 * r * r * std::acos(d / (2 * r)) - 0.5 * d * std::sqrt(4 * r * r - d * d);
    return lens / (2 * kPi * r * r - lens);
}

TEST(EllipseOverlap, EqualCirclesOffsetMatchTheClosedForm) {
    const double r = 30;
    double worst = 0;
    for (double d : {0.0, 0.3, 3.0, 6.0, 15.0, 30.0, 45.0, 59.0, 59.9, 60.0, 75.0}) {
        SCOPED_TRACE(d);
        double expected = equal_circles_overlap(r, d);
        double measured =
            ellipse_overlap(Ellipse::circle({100, 50}, r), Ellipse::circle({100 + d * 0.6, 50 + d * 0.8}, r));
        EXPECT_NEAR(measured, expected, 1e-5);
        worst = std::max(worst, std::abs(measured - expected));
    }
    RecordProperty("worst_error", ::testing::PrintToString(worst));
}

TEST(EllipseOverlap, ConcentricCirclesGiveTheAreaRatio) {
    EXPECT_NEAR(ellipse_overlap(Ellipse::circle({0, 0}, 10), Ellipse::circle({0, 0}, 20)), 0.25, 1e-5);
    EXPECT_NEAR(ellipse_overlap(Ellipse::circle({0, 0}, 20), Ellipse::circle({1, 2}, 10)), 0.25, 1e-5);
}

TEST(EllipseOverlap, PerpendicularEllipsesMatchTheClosedForm) {
    // x^2/a^2 + y^2/b^2 <= 1 and x^2/b^2 + y^2/a^2 <= 1 share 4 a b atan(b / a).
    const double a = 40, b = 10;
    Ellipse wide{{5, 5}, Eigen::Vector2d(1 / (a * a), 1 / (b * b)).asDiagonal()};
    Ellipse tall{{5, 5}, Eigen::Vector2d(1 / (b * b), 1 / (a * a)).asDiagonal()};
    double common = 4 * a * b * std::atan(b / a);
    EXPECT_NEAR(ellipse_overlap(wide, tall), common / (2 * kPi * a * b - common), 1e-5);
}

TEST(EllipseOverlap, IsInvariantUnderACommonAffineMap) {
    Ellipse a{{3, 4}, (Eigen::Matrix2d() << 0.02, 0.005, 0.005, 0.01).finished()};
    Ellipse b{{6, 2}, (Eigen::Matrix2d() << 0.015, -0.004, -0.004, 0.02).finished()};
    Eigen::Matrix2d affine;
    affine << 1.7, 0.4, -0.3, 0.8;
    Eigen::Vector2d shift(50, -20);
    double before = ellipse_overlap(a, b);
    double after = ellipse_overlap(map_ellipse(a, affine * a.centre + shift, affine),
                                   map_ellipse(b, affine * b.centre + shift, affine));
    EXPECT_GT(before, 0.3);  // a real partial overlap, not a trivial 0 or 1
    EXPECT_LT(before, 0.9);
    EXPECT_NEAR(after, before, 2e-5);
    EXPECT_NEAR(ellipse_overlap(b, a), before, 2e-5);
}

TEST(Ellipse, AreaExtentAndScaling) {
    Ellipse e{{0, 0}, Eigen::Vector2d(1.0 / 100, 1.0 / 25).asDiagonal()};  // semi-axes 10, 5
    EXPECT_NEAR(e.area(), kPi * 50, 1e-9);
    EXPECT_NEAR(e.equivalent_radius(), std::sqrt(50.0), 1e-12);
    EXPECT_NEAR(e.half_extent().x(), 10, 1e-12);
    EXPECT_NEAR(e.half_extent().y(), 5, 1e-12);
    EXPECT_NEAR(e.scaled(3).area(), 9 * kPi * 50, 1e-9);
    EXPECT_EQ(e.scaled(3).centre, e.centre);
}

TEST(Ellipse, MapThroughAnAffineMap) {
    Ellipse c = Ellipse::circle({10, 10}, 5);
    Eigen::Matrix2d stretch = Eigen::Vector2d(2, 1).asDiagonal();
    Ellipse e = map_ellipse(c, {30, 40}, stretch);
    EXPECT_EQ(e.centre, Eigen::Vector2d(30, 40));
    EXPECT_NEAR(e.half_extent().x(), 10, 1e-12);
    EXPECT_NEAR(e.half_extent().y(), 5, 1e-12);
    EXPECT_NEAR(e.area(), 2 * kPi * 25, 1e-9);
}

TEST(Ellipse, MapThroughAHomographyUsesItsJacobian) {
    Eigen::Matrix3d h;
    h << 0.76, -0.3, 225.7, 0.33, 1.01, -77.0, 3.5e-4, -1.4e-5, 1.0;
    Eigen::Vector2d p(300, 200);
    // Jacobian against central differences.
    const double step = 1e-3;
    Eigen::Matrix2d numeric;
    for (int k = 0; k < 2; ++k) {
        Eigen::Vector2d dp = Eigen::Vector2d::Zero();
        dp[k] = step;
        numeric.col(k) = (apply_homography(h, p + dp) - apply_homography(h, p - dp)) / (2 * step);
    }
    Eigen::Matrix2d j = homography_jacobian(h, p);
    EXPECT_LT((j - numeric).cwiseAbs().maxCoeff(), 1e-7);
    // A small circle maps onto the points its boundary maps to (to first order).
    Ellipse c = Ellipse::circle(p, 0.5);
    Ellipse e = map_ellipse(c, h);
    EXPECT_LT((e.centre - apply_homography(h, p)).norm(), 1e-9);
    for (double angle = 0; angle < 6.28; angle += 0.5) {
        Eigen::Vector2d q = apply_homography(h, p + 0.5 * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
        Eigen::Vector2d u = q - e.centre;
        EXPECT_NEAR(u.dot(e.m * u), 1.0, 1e-3);
    }
}

}  // namespace
}  // namespace surfvp::eval
