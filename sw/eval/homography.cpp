#include "sw/eval/homography.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include "sw/eval/text_io.h"

namespace surfvp::eval {

namespace {

// FileStorage files announce themselves in their first characters.
bool looks_like_file_storage(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::string start(16, '\0');
    in.read(start.data(), static_cast<std::streamsize>(start.size()));
    start.resize(static_cast<std::size_t>(in.gcount()));
    std::size_t i = 0;
    while (i < start.size() && std::isspace(static_cast<unsigned char>(start[i]))) ++i;
    start.erase(0, i);
    return start.rfind("<?xml", 0) == 0 || start.rfind("<opencv_storage", 0) == 0 ||
           start.rfind("%YAML", 0) == 0 || start.rfind("{", 0) == 0;
}

Eigen::Matrix3d read_file_storage(const std::filesystem::path& file) {
    cv::FileStorage storage;
    try {
        storage.open(file.string(), cv::FileStorage::READ);
    } catch (const cv::Exception& e) {
        throw FormatError(file, 0, "OpenCV cannot parse it: " + e.msg);
    } catch (const std::length_error& e) {  // OpenCV 4.6's YAML parser on some broken files
        throw FormatError(file, 0, std::string("OpenCV cannot parse it: ") + e.what());
    }
    if (!storage.isOpened()) throw FormatError(file, 0, "OpenCV cannot open it as a FileStorage");
    for (const auto& node : storage.root()) {
        // OpenCV allocates rows x cols before it reads the data: a small file declaring a huge
        // matrix would ask for gigabytes. Only a 3x3 node can be the homography.
        if (!node.isMap() || int(node["rows"]) != 3 || int(node["cols"]) != 3) continue;
        cv::Mat m;
        try {
            node >> m;
        } catch (const cv::Exception&) {
            continue;  // not a matrix node
        }
        if (m.rows != 3 || m.cols != 3 || m.channels() != 1) continue;
        m.convertTo(m, CV_64F);
        Eigen::Matrix3d h;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) h(r, c) = m.at<double>(r, c);
        return h;
    }
    throw FormatError(file, 0, "no 3x3 matrix at the top level of the FileStorage");
}

Eigen::Matrix3d read_plain_text(const std::filesystem::path& file) {
    TextReader reader(file);
    std::vector<std::string_view> t;
    Eigen::Matrix3d h;
    for (int row = 0; row < 3; ++row) {
        if (!reader.next(t)) {
            throw FormatError(file, reader.line(), "file ends after " + std::to_string(row) +
                                                       " of the 3 rows of the homography");
        }
        if (t.size() != 3) reader.fail("expected 3 values, found " + std::to_string(t.size()));
        for (int col = 0; col < 3; ++col) h(row, col) = reader.real(t[col], "matrix element");
    }
    if (reader.next(t)) reader.fail("more than the 3 rows of the homography");
    return h;
}

}  // namespace

Eigen::Matrix3d read_homography_file(const std::filesystem::path& file) {
    if (!std::filesystem::exists(file)) throw std::runtime_error(file.string() + ": no such file");
    if (!std::filesystem::is_regular_file(file)) {
        throw std::runtime_error(file.string() + ": not a regular file (a folder, a FIFO or a device is not read)");
    }
    Eigen::Matrix3d h = looks_like_file_storage(file) ? read_file_storage(file) : read_plain_text(file);
    if (!h.allFinite()) throw FormatError(file, 0, "the homography has non-finite elements");
    // Scale-free singularity test: |det H| against the product of the row norms.
    double scale = h.row(0).norm() * h.row(1).norm() * h.row(2).norm();
    if (!(std::abs(h.determinant()) > 1e-12 * scale)) {
        throw FormatError(file, 0, "the homography is singular");
    }
    return h;
}

Eigen::Vector2d apply_homography(const Eigen::Matrix3d& h, const Eigen::Vector2d& p) {
    return (h * p.homogeneous()).hnormalized();
}

Eigen::Matrix2d homography_jacobian(const Eigen::Matrix3d& h, const Eigen::Vector2d& p) {
    // q = (h0 . p~) / w, w = h2 . p~  =>  dq/dp = (H[0:2, 0:2] - q h2[0:2]) / w
    Eigen::Vector3d x = h * p.homogeneous();
    double w = x.z();
    Eigen::Vector2d q = x.head<2>() / w;
    return (h.topLeftCorner<2, 2>() - q * h.block<1, 2>(2, 0)) / w;
}

Eigen::Matrix3d translation_homography(double dx, double dy) {
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h(0, 2) = dx;
    h(1, 2) = dy;
    return h;
}

}  // namespace surfvp::eval
