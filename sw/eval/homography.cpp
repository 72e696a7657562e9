#include "sw/eval/homography.h"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include "models/host/yaml_text.h"
#include "sw/eval/text_io.h"

namespace surfvp::eval {

namespace {

enum class Format { plain_text, yaml, opencv };  // opencv: FileStorage XML or JSON

// FileStorage files announce themselves in their first 16 characters.
Format format_of(const std::string& text) {
    const std::string head = text.substr(0, 16);
    const std::size_t start = std::min(head.find_first_not_of(" \t\n\v\f\r"), head.size());
    auto starts_with = [&](const char* word) { return head.compare(start, std::strlen(word), word) == 0; };
    if (starts_with("%YAML")) return Format::yaml;
    if (starts_with("<?xml") || starts_with("<opencv_storage") || starts_with("{")) return Format::opencv;
    return Format::plain_text;
}

// The YAML form of a FileStorage (as OpenCV writes it: a "%YAML:1.0" line, then a map whose
// matrices are maps of rows, cols, dt and data), read with yaml-cpp: OpenCV 4.6's own YAML
// parser never returns on some 20-byte files (found by tests/fuzz homography: "%YAML:1.\n L:0\n--3-\n").
Eigen::Matrix3d read_yaml(const std::filesystem::path& file, std::string text) {
    // OpenCV's header is no YAML directive ("%YAML 1.0" is): blank it, keeping the line count.
    const std::size_t header = text.find('%');
    if (text.compare(header, 6, "%YAML:") == 0) text.replace(header, text.find('\n', header) - header, "");
    YAML::Node root;
    try {
        root = load_yaml(text);
    } catch (const YAML::Exception& e) {
        throw FormatError(file, std::size_t(e.mark.line + 1), "not YAML: " + e.msg);
    }
    if (root.IsMap()) {
        for (const auto& entry : root) {
            const YAML::Node& m = entry.second;
            if (!m.IsMap() || !m["rows"] || !m["cols"] || !m["dt"] || !m["data"]) continue;
            const YAML::Node data = m["data"];
            // Single-channel element types only ("3d" is a matrix of 3-vectors).
            const std::string dt = m["dt"].IsScalar() ? m["dt"].Scalar() : "";
            if (m["rows"].Scalar() != "3" || m["cols"].Scalar() != "3" || dt.size() != 1 ||
                std::string("ucwsifd").find(dt[0]) == std::string::npos || !data.IsSequence() || data.size() != 9)
                continue;
            Eigen::Matrix3d h;
            for (std::size_t k = 0; k < 9; ++k) {
                double v = 0;
                if (!data[k].IsScalar() || !YAML::convert<double>::decode(data[k], v))
                    throw FormatError(file, std::size_t(data[k].Mark().line + 1),
                                      "matrix element " + std::to_string(k) + " is not a number");
                h(int(k / 3), int(k % 3)) = dt == "f" ? double(float(v)) : v;  // as OpenCV reads a float matrix
            }
            return h;
        }
    }
    throw FormatError(file, 0, "no 3x3 matrix at the top level of the YAML file");
}

Eigen::Matrix3d read_file_storage(const std::filesystem::path& file, const std::string& text) {
    // Neither XML nor JSON holds a NUL byte, and OpenCV 4.6's XML parser dereferences a null
    // pointer on one in the XML declaration (found by tests/fuzz homography).
    const auto line_of = [&](std::size_t at) {
        return std::size_t(std::count(text.begin(), text.begin() + long(at), '\n') + 1);
    };
    if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
        throw FormatError(file, line_of(nul), "a NUL byte: not a text file");
    // It does so too when the file ends after an attribute's '=' (and spaces), in the XML
    // declaration or in a tag (found by tests/fuzz homography).
    if (const std::size_t last = text.find_last_not_of(" \t\r\n"); last != std::string::npos && text[last] == '=')
        throw FormatError(file, line_of(last), "the file ends after an '=': an attribute without its value");
    cv::FileStorage storage;
    try {
        storage.open(file.string(), cv::FileStorage::READ);
    } catch (const cv::Exception& e) {
        throw FormatError(file, 0, "OpenCV cannot parse it: " + e.msg);
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
            throw FormatError(file, reader.line(),
                              "file ends after " + std::to_string(row) + " of the 3 rows of the homography");
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
    std::ifstream in(file, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const Format format = format_of(text);
    Eigen::Matrix3d h = format == Format::yaml     ? read_yaml(file, text)
                        : format == Format::opencv ? read_file_storage(file, text)
                                                   : read_plain_text(file);
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
