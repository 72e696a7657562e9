#include "sw/eval/pose_geometry.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "sw/eval/text_io.h"

namespace surfvp::eval {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d s;
    s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return s;
}

void check_rigid(const TextReader& reader, const Eigen::Matrix4d& m) {
    // The last line has just been read: errors point at it or at the file as a whole.
    Eigen::RowVector4d last(0, 0, 0, 1);
    if ((m.row(3) - last).cwiseAbs().maxCoeff() > 1e-9) reader.fail("last row is not 0 0 0 1");
    Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
    double error = (r * r.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (error > 1e-5 || r.determinant() < 0) {
        throw FormatError(
            reader.file(), 0,
            "the 3x3 rotation is not orthonormal with determinant +1 (|R R^T - I| = " + std::to_string(error) + ")");
    }
}

// "Prefix_<digits>.ext" -> digits, for Camera_012.txt and Image_0012.pgm.
std::optional<unsigned> frame_number(const std::filesystem::path& file, const std::string& prefix) {
    std::string stem = file.stem().string();
    if (stem.rfind(prefix, 0) != 0 || stem.size() == prefix.size()) return std::nullopt;
    std::string digits = stem.substr(prefix.size());
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) || digits.size() > 9) {
        return std::nullopt;
    }
    return static_cast<unsigned>(std::stoul(digits));
}

std::map<unsigned, std::filesystem::path> numbered_files(const std::filesystem::path& folder,
                                                         const std::string& prefix) {
    if (!std::filesystem::is_directory(folder)) {
        throw std::runtime_error(folder.string() + ": no such folder");
    }
    std::map<unsigned, std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        if (!entry.is_regular_file()) continue;
        auto n = frame_number(entry.path(), prefix);
        if (!n) continue;
        if (!files.emplace(*n, entry.path()).second) {
            throw std::runtime_error(folder.string() + ": two files for frame " + std::to_string(*n) + ": " +
                                     files[*n].filename().string() + " and " + entry.path().filename().string());
        }
    }
    return files;
}

}  // namespace

Eigen::Matrix3d CameraIntrinsics::matrix() const {
    Eigen::Matrix3d k;
    k << px, 0, u0, 0, py, v0, 0, 0, 1;
    return k;
}

Eigen::Matrix4d read_pose_file(const std::filesystem::path& file) {
    TextReader reader(file);
    std::vector<std::string_view> t;
    Eigen::Matrix4d m;
    for (int row = 0; row < 4; ++row) {
        if (!reader.next(t)) {
            throw FormatError(file, reader.line(),
                              "file ends after " + std::to_string(row) + " of the 4 rows of the pose matrix");
        }
        if (t.size() != 4) reader.fail("expected 4 values, found " + std::to_string(t.size()));
        for (int col = 0; col < 4; ++col) m(row, col) = reader.real(t[col], "matrix element");
    }
    check_rigid(reader, m);
    if (reader.next(t)) reader.fail("more than the 4 rows of the pose matrix");
    return m;
}

Eigen::Vector2d project(const CameraIntrinsics& k, const Eigen::Matrix4d& c_m_o, const Eigen::Vector3d& x_o) {
    Eigen::Vector3d x_c = c_m_o.topLeftCorner<3, 3>() * x_o + c_m_o.topRightCorner<3, 1>();
    return {k.u0 + k.px * x_c.x() / x_c.z(), k.v0 + k.py * x_c.y() / x_c.z()};
}

Eigen::Matrix3d fundamental_from_poses(const CameraIntrinsics& k_a, const Eigen::Matrix4d& a_m_o,
                                       const CameraIntrinsics& k_b, const Eigen::Matrix4d& b_m_o) {
    // The true inverse rather than the transpose: pose files print single-precision rotations
    // (orthonormal to ~1e-7), and over the castle's 0.7 mm neighbour baselines R_a^T instead of
    // R_a^-1 would cost 1e-5 px. With the inverse, X_b = R X_a + t holds exactly for the poses
    // as stored, and so does X_b^T E X_a = 0 (X_b . t x (X_b - t) = 0 for any R).
    Eigen::Matrix4d b_m_a = b_m_o * a_m_o.inverse();
    Eigen::Matrix3d r = b_m_a.topLeftCorner<3, 3>();
    Eigen::Vector3d t = b_m_a.topRightCorner<3, 1>();
    if (t.norm() < 1e-12) {
        throw std::invalid_argument("fundamental_from_poses: the camera centres coincide");
    }
    Eigen::Matrix3d e = skew(t) * r;
    Eigen::Matrix3d f = k_b.matrix().inverse().transpose() * e * k_a.matrix().inverse();
    return f / f.norm();
}

std::vector<PosedFrame> list_posed_frames(const std::filesystem::path& sequence_folder) {
    auto images = numbered_files(sequence_folder / "Images", "Image_");
    auto poses = numbered_files(sequence_folder / "CameraPose", "Camera_");
    if (poses.empty()) {
        throw std::runtime_error((sequence_folder / "CameraPose").string() + ": no Camera_<n>.txt pose files");
    }
    std::vector<PosedFrame> frames;
    for (const auto& [n, pose] : poses) {
        auto image = images.find(n);
        if (image == images.end()) {
            throw std::runtime_error(pose.string() + ": no image Image_<" + std::to_string(n) + ">.* in " +
                                     (sequence_folder / "Images").string());
        }
        frames.push_back({n, image->second, pose, read_pose_file(pose)});
    }
    for (const auto& [n, image] : images) {
        if (!poses.count(n)) {
            throw std::runtime_error(image.string() + ": no pose Camera_<" + std::to_string(n) + ">.txt in " +
                                     (sequence_folder / "CameraPose").string());
        }
    }
    return frames;
}

}  // namespace surfvp::eval
