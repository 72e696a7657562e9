#pragma once
// Ground-truth epipolar geometry from camera poses, for distinguishability without RANSAC.
// Poses follow ViSP: cMo is the 4x4 rigid transform from the object frame to the camera frame,
// X_c = R X_o + t; pixels are u = u0 + px X_c/Z_c, v = v0 + py Y_c/Z_c. The simulated castle
// sequence of the Debian package visp-images-data (mbt-depth/Castle-simu) provides one
// CameraPose/Camera_NNN.txt per Images/Image_NNNN.pgm.
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "sw/eval/format_error.h"

namespace surfvp::eval {

struct CameraIntrinsics {
    double px = 0, py = 0;  // focal lengths, pixels
    double u0 = 0, v0 = 0;  // principal point, pixels

    Eigen::Matrix3d matrix() const;  // K
};

// Castle-simu/Config/chateau.xml.
inline constexpr CameraIntrinsics kCastleIntrinsics{700, 700, 320, 240};

// A pose file: four lines of four numbers, the last 0 0 0 1, the rotation orthonormal to 1e-5
// (the files print single-precision values). Throws FormatError.
Eigen::Matrix4d read_pose_file(const std::filesystem::path& file);

// Pixel position of the object-frame point X_o seen by a camera with pose cMo.
Eigen::Vector2d project(const CameraIntrinsics& k, const Eigen::Matrix4d& c_m_o, const Eigen::Vector3d& x_o);

// F with x_b^T F x_a = 0 for pixels x_a, x_b of the same scene point in cameras a and b:
//   relative pose  bMa = bMo aMo^-1 = [R t; 0 1]   (R = R_b R_a^T, t = t_b - R t_a for exact
//                  rotations; the 4x4 inverse is used so stored float rotations stay exact)
//   essential      E = [t]x R         (X_b^T E X_a = 0 in camera coordinates)
//   fundamental    F = K_b^-T E K_a^-1, scaled to unit Frobenius norm.
// Throws std::invalid_argument when the camera centres coincide (|t| < 1e-12: F undefined).
Eigen::Matrix3d fundamental_from_poses(const CameraIntrinsics& k_a, const Eigen::Matrix4d& a_m_o,
                                       const CameraIntrinsics& k_b, const Eigen::Matrix4d& b_m_o);

inline Eigen::Matrix3d fundamental_from_poses(const CameraIntrinsics& k, const Eigen::Matrix4d& a_m_o,
                                              const Eigen::Matrix4d& b_m_o) {
    return fundamental_from_poses(k, a_m_o, k, b_m_o);
}

struct PosedFrame {
    unsigned number = 0;  // NNN of Camera_NNN.txt and Image_NNNN.*
    std::filesystem::path image;
    std::filesystem::path pose_file;
    Eigen::Matrix4d c_m_o;
};

// The frames of a ViSP sequence folder (Images/Image_<n>.<ext> + CameraPose/Camera_<n>.txt),
// ordered by n. Throws std::runtime_error naming what is missing: either folder, or the image
// of a pose or the pose of an image.
std::vector<PosedFrame> list_posed_frames(const std::filesystem::path& sequence_folder);

}  // namespace surfvp::eval
