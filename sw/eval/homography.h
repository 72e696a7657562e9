#pragma once
// Homographies between the images of a planar scene (Oxford affine data set: H1to2p .. H1to6p
// map pixels of image 1 to image n) and what repeatability needs of them: the point map and its
// local affine approximation. Pixel coordinates as in the keypoints, origin (0, 0) at the centre
// of the top-left pixel (vlbenchmarks: "the homography assumes image coordinates with origin in
// (0,0)").
#include <filesystem>

#include <Eigen/Core>

#include "sw/eval/format_error.h"

namespace surfvp::eval {

// Reads either an Oxford plain text file (three lines of three numbers) or an OpenCV
// FileStorage file (XML, YAML or JSON, e.g. opencv-doc's H1to3p.xml) holding a 3x3 matrix (the
// first 3x3 matrix node at the top level). Throws FormatError for anything else, a singular or
// non-finite matrix included.
Eigen::Matrix3d read_homography_file(const std::filesystem::path& file);

Eigen::Vector2d apply_homography(const Eigen::Matrix3d& h, const Eigen::Vector2d& p);

// The Jacobian of p -> apply_homography(h, p) at p: the local affine approximation.
Eigen::Matrix2d homography_jacobian(const Eigen::Matrix3d& h, const Eigen::Vector2d& p);

// x' = x + dx, y' = y + dy, for tests and synthetic data.
Eigen::Matrix3d translation_homography(double dx, double dy);

}  // namespace surfvp::eval
