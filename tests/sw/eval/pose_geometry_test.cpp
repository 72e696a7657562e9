// Ground-truth F from the real camera poses of ViSP's simulated castle sequence (Debian package
// visp-images-data).
#include "sw/eval/pose_geometry.h"

#include <cmath>
#include <fstream>
#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "sw/eval/eval_test_support.h"
#include "sw/eval/distinguishability.h"

namespace surfvp::eval {
namespace {

using test::Random;

const std::filesystem::path kCastle = std::filesystem::path(VISP_DATA_DIR) / "mbt-depth/Castle-simu";

std::vector<PosedFrame> castle_frames() { return list_posed_frames(kCastle); }

#define REQUIRE_CASTLE() ASSERT_TRUE(test::package_file(kCastle / "CameraPose/Camera_001.txt", "visp-images-data"))

TEST(PoseGeometry, ReadsACastlePose) {
    REQUIRE_CASTLE();
    Eigen::Matrix4d m = read_pose_file(kCastle / "CameraPose/Camera_001.txt");
    EXPECT_EQ(m(0, 0), 1.0);
    EXPECT_EQ(m(0, 3), 0.05000004917383194);
    EXPECT_EQ(m(1, 1), -0.9063078165054321);
    EXPECT_EQ(m(2, 3), 0.6010702848434448);
    EXPECT_EQ(m.row(3), Eigen::RowVector4d(0, 0, 0, 1));
}

TEST(PoseGeometry, ListsTheFortyCastleFrames) {
    REQUIRE_CASTLE();
    auto frames = castle_frames();
    ASSERT_EQ(frames.size(), 40u);
    for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(frames[i].number, i + 1);
    EXPECT_EQ(frames.front().image.filename(), "Image_0001.pgm");
    EXPECT_EQ(frames.front().pose_file.filename(), "Camera_001.txt");
    EXPECT_EQ(frames.back().image.filename(), "Image_0040.pgm");
    EXPECT_EQ(frames.back().c_m_o, read_pose_file(kCastle / "CameraPose/Camera_040.txt"));
}

// Random object-frame points in front of both cameras (at least 5 cm), as pixels in each.
struct Projections {
    std::vector<Eigen::Vector2d> a, b;
};

Projections project_points(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b, std::size_t n, Random& random) {
    Projections p;
    while (p.a.size() < n) {
        Eigen::Vector3d x(random.uniform(-0.15, 0.15), random.uniform(-0.15, 0.15), random.uniform(-0.15, 0.15));
        double za = (a.topLeftCorner<3, 3>() * x + a.topRightCorner<3, 1>()).z();
        double zb = (b.topLeftCorner<3, 3>() * x + b.topRightCorner<3, 1>()).z();
        if (za < 0.05 || zb < 0.05) continue;
        p.a.push_back(project(kCastleIntrinsics, a, x));
        p.b.push_back(project(kCastleIntrinsics, b, x));
    }
    return p;
}

TEST(PoseGeometry, CastleFundamentalMatrixHoldsForProjectedPoints) {
    REQUIRE_CASTLE();
    auto frames = castle_frames();
    Random random(41);
    // Neighbours (small baseline), and frames far apart (large baseline).
    for (auto [i, j] : {std::pair{0, 1}, std::pair{0, 19}, std::pair{9, 39}, std::pair{25, 12}}) {
        SCOPED_TRACE(std::to_string(i + 1) + " -> " + std::to_string(j + 1));
        const Eigen::Matrix4d &a = frames[i].c_m_o, &b = frames[j].c_m_o;
        Eigen::Matrix3d f = fundamental_from_poses(kCastleIntrinsics, a, b);
        EXPECT_NEAR(f.norm(), 1.0, 1e-12);
        Eigen::JacobiSVD<Eigen::Matrix3d> svd(f);
        EXPECT_LT(svd.singularValues()(2), 1e-12 * svd.singularValues()(0));  // rank 2
        Eigen::Matrix3d back = fundamental_from_poses(kCastleIntrinsics, b, a);

        Projections p = project_points(a, b, 200, random);
        double worst_algebraic = 0, worst_distance = 0;
        for (std::size_t k = 0; k < p.a.size(); ++k) {
            Eigen::Vector3d xa = p.a[k].homogeneous(), xb = p.b[k].homogeneous();
            // x_b^T F x_a relative to its terms' size; the distance in pixels.
            worst_algebraic = std::max(worst_algebraic, std::abs(xb.dot(f * xa)) / (xb.norm() * xa.norm()));
            worst_distance = std::max(
                {worst_distance, epipolar_distance(f, p.a[k], p.b[k]), epipolar_distance(back, p.b[k], p.a[k])});
            // The measure is not blind: 2 px across the line are measured as 2 px.
            Eigen::Vector2d normal = (f * xa).head<2>().normalized();
            EXPECT_NEAR(epipolar_distance(f, p.a[k], p.b[k] + 2.0 * normal), 2.0, 1e-6);
        }
        EXPECT_LT(worst_algebraic, 1e-12);
        EXPECT_LT(worst_distance, 1e-6);  // px; measured ~5e-13 (double rounding)
        RecordProperty("worst_distance_" + std::to_string(i + 1) + "_" + std::to_string(j + 1),
                       ::testing::PrintToString(worst_distance));
    }
}

TEST(PoseGeometry, CastleKeypointsAreDistinguishableUnderTheTruePoses) {
    REQUIRE_CASTLE();
    auto frames = castle_frames();
    Random random(42);
    Projections p = project_points(frames[0].c_m_o, frames[9].c_m_o, 150, random);
    surf::Keypoints a, b;
    for (std::size_t k = 0; k < p.a.size(); ++k) {
        surf::Keypoint kp = test::random_keypoint(random, 1, 1);
        kp.x = static_cast<float>(p.a[k].x()), kp.y = static_cast<float>(p.a[k].y());
        a.push_back(kp);
        kp.x = static_cast<float>(p.b[k].x()), kp.y = static_cast<float>(p.b[k].y());
        b.push_back(kp);
    }
    Eigen::Matrix3d truth = fundamental_from_poses(kCastleIntrinsics, frames[0].c_m_o, frames[9].c_m_o);
    EXPECT_EQ(distinguishability(a, b, truth).distinguishability, 1.0);
    EXPECT_EQ(distinguishability(a, b).distinguishability, 1.0);  // RANSAC
    // The geometry of another pair rejects most of them.
    Eigen::Matrix3d other = fundamental_from_poses(kCastleIntrinsics, frames[0].c_m_o, frames[30].c_m_o);
    double wrong = distinguishability(a, b, other).distinguishability;
    EXPECT_LT(wrong, 0.5);
    RecordProperty("distinguishability_other_pair_f", ::testing::PrintToString(wrong));
}

TEST(PoseGeometry, SwappingExactCamerasTransposesF) {
    Eigen::Matrix4d a = Eigen::Matrix4d::Identity(), b = Eigen::Matrix4d::Identity();
    a.topLeftCorner<3, 3>() = Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    a.topRightCorner<3, 1>() = Eigen::Vector3d(0.1, -0.2, 0.7);
    b.topLeftCorner<3, 3>() = Eigen::AngleAxisd(-0.1, Eigen::Vector3d(0, 1, 0.2).normalized()).toRotationMatrix();
    b.topRightCorner<3, 1>() = Eigen::Vector3d(-0.05, 0.1, 0.6);
    Eigen::Matrix3d f = fundamental_from_poses(kCastleIntrinsics, a, b);
    Eigen::Matrix3d back = fundamental_from_poses(kCastleIntrinsics, b, a);
    EXPECT_LT(std::min((back - f.transpose()).norm(), (back + f.transpose()).norm()), 1e-12);
}

TEST(PoseGeometry, CoincidentCentresHaveNoFundamentalMatrix) {
    Eigen::Matrix4d a = Eigen::Matrix4d::Identity(), b = a;
    b.topLeftCorner<3, 3>() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_THROW(fundamental_from_poses(kCastleIntrinsics, a, b), std::invalid_argument);
}

TEST(PoseGeometry, MalformedPoseFilesAreNamed) {
    test::TemporaryFolder dir;
    std::ofstream(dir / "short.txt") << "1 0 0 0\n0 1 0 0\n0 0 1 0\n";
    std::ofstream(dir / "skewed.txt") << "1 0.1 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
    std::ofstream(dir / "row.txt") << "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 1 1\n";
    std::ofstream(dir / "word.txt") << "1 0 0 0\n0 1 x 0\n0 0 1 0\n0 0 0 1\n";
    struct Case {
        const char* file;
        std::size_t line;
        const char* problem;
    };
    for (const Case& c :
         {Case{"short.txt", 3, "file ends after 3 of the 4 rows"}, Case{"skewed.txt", 0, "not orthonormal"},
          Case{"row.txt", 4, "last row is not 0 0 0 1"}, Case{"word.txt", 2, "'x' is not a number"}}) {
        SCOPED_TRACE(c.file);
        try {
            read_pose_file(dir / c.file);
            ADD_FAILURE() << "no FormatError";
        } catch (const FormatError& e) {
            EXPECT_EQ(e.file(), dir / c.file);
            EXPECT_EQ(e.line(), c.line);
            EXPECT_NE(e.problem().find(c.problem), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(list_posed_frames(dir.path()), std::runtime_error);  // no Images, CameraPose
}

}  // namespace
}  // namespace surfvp::eval
