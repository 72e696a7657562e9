#include "sw/eval/keypoint_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "sw/eval/region.h"
#include "sw/eval/text_io.h"

namespace surfvp::eval {

namespace {

constexpr std::size_t kDescriptorSize = std::tuple_size_v<decltype(surf::Keypoint::descriptor)>;
constexpr std::size_t kMaxKeypoints = 100'000'000;

void check_writable(const surf::Keypoint& k, std::size_t index) {
    bool finite = std::isfinite(k.x) && std::isfinite(k.y) && std::isfinite(k.orientation) && std::isfinite(k.response);
    for (float d : k.descriptor) finite = finite && std::isfinite(d);
    if (!finite || !(k.scale > 0) || !std::isfinite(k.scale)) {
        throw std::invalid_argument(
            fmt::format("keypoint {}: needs finite values and a positive scale (scale {})", index, k.scale));
    }
}

// A value as printf's %.9g writes it (9 significant digits: a float's value read back exactly),
// through std::to_chars: ~40 % less time than fmt's "{:.9g}" for the same bytes, and a run
// writes ~7000 values a frame.
void put_g9(fmt::memory_buffer& out, double v) {
    char text[32];
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, v, std::chars_format::general, 9);
    out.append(text, r.ptr);
}

// The values, each after a space but the first.
void put_line(fmt::memory_buffer& out, std::initializer_list<double> values) {
    for (const double* v = values.begin(); v != values.end(); ++v) {
        if (v != values.begin()) out.push_back(' ');
        put_g9(out, *v);
    }
}

std::string format_keypoints(const surf::Keypoints& keypoints, bool laplacian) {
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "{}\n{}\n", kDescriptorSize + (laplacian ? 1 : 0), keypoints.size());
    for (const auto& k : keypoints) {
        double r = region_radius(k);
        double a = 1.0 / (r * r);
        put_line(out, {k.x, k.y, a});
        out.append(std::string_view(" 0 "));
        put_g9(out, a);
        if (laplacian) fmt::format_to(std::back_inserter(out), FMT_COMPILE(" {}"), k.laplacian);
        for (float d : k.descriptor) {
            out.push_back(' ');
            put_g9(out, d);
        }
        out.push_back('\n');
    }
    return fmt::to_string(out);
}

std::string format_meta(const surf::Keypoints& keypoints) {
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "{}\n", keypoints.size());
    for (const auto& k : keypoints) {
        put_line(out, {k.x, k.y, k.scale, k.orientation, k.response});
        fmt::format_to(std::back_inserter(out), FMT_COMPILE(" {}\n"), k.laplacian);
    }
    return fmt::to_string(out);
}

int read_laplacian(const TextReader& reader, std::string_view token) {
    double value = reader.real(token, "Laplacian sign");
    if (value != -1 && value != 0 && value != 1) {
        reader.fail("Laplacian sign '" + std::string(token) + "' is not -1, 0 or +1");
    }
    return static_cast<int>(value);
}

// The header: dimension then count, each alone on its line.
std::size_t read_header_value(TextReader& reader, std::vector<std::string_view>& tokens, const char* what,
                              std::size_t max) {
    if (!reader.next(tokens)) {
        throw FormatError(reader.file(), reader.line(), std::string("file ends before the ") + what);
    }
    if (tokens.size() != 1) {
        reader.fail(std::string("expected the ") + what + " alone on the line, found " + std::to_string(tokens.size()) +
                    " values");
    }
    return reader.count(tokens[0], what, max);
}

unsigned read_dimension(TextReader& reader, std::vector<std::string_view>& tokens) {
    std::size_t dimension = read_header_value(reader, tokens, "descriptor dimension", 1'000'000);
    if (dimension <= 1) return 0;  // Mikolajczyk's detector-only files write 0 or 1
    if (dimension != kDescriptorSize && dimension != kDescriptorSize + 1) {
        reader.fail("descriptor dimension " + std::to_string(dimension) +
                    " is not supported: expected 0 or 1 (none), 64, or 65 (Laplacian sign + 64)");
    }
    return static_cast<unsigned>(dimension);
}

surf::Keypoint parse_keypoint(const TextReader& reader, const std::vector<std::string_view>& t, unsigned dimension) {
    std::size_t expected = 5 + dimension;
    if (t.size() != expected) {
        reader.fail("expected " + std::to_string(expected) + " values (x y a b c" +
                    (dimension ? " + " + std::to_string(dimension) + " descriptor values" : "") + "), found " +
                    std::to_string(t.size()));
    }
    surf::Keypoint k;
    k.x = reader.real_float(t[0], "x");
    k.y = reader.real_float(t[1], "y");
    double a = reader.real(t[2], "a"), b = reader.real(t[3], "b"), c = reader.real(t[4], "c");
    double det = a * c - b * b;
    if (!(a > 0) || !(c > 0) || !(det > 0)) {
        reader.fail("ellipse a b c = " + std::string(t[2]) + " " + std::string(t[3]) + " " + std::string(t[4]) +
                    " is not positive definite");
    }
    // The radius of the circle with the ellipse's area, pi / sqrt(det).
    k.scale = static_cast<float>(std::pow(det, -0.25) / kRegionRadiusPerScale);
    if (!(k.scale > 0) || !std::isfinite(k.scale)) {  // found by tests/fuzz (keypoint_file): 0 once rounded to a float
        reader.fail("ellipse a b c = " + std::string(t[2]) + " " + std::string(t[3]) + " " + std::string(t[4]) +
                    " gives a scale beyond a float's range");
    }
    std::size_t first = 5;
    if (dimension == kDescriptorSize + 1) k.laplacian = read_laplacian(reader, t[first++]);
    if (dimension > 0) {
        for (std::size_t i = 0; i < kDescriptorSize; ++i) {
            k.descriptor[i] = reader.real_float(t[first + i], "descriptor value");
        }
    }
    return k;
}

// Applies NAME.meta to keypoints read from NAME: same count, same positions.
void apply_meta(const std::filesystem::path& file, surf::Keypoints& keypoints, bool has_sign) {
    TextReader reader(file);
    std::vector<std::string_view> t;
    std::size_t n = read_header_value(reader, t, "keypoint count", kMaxKeypoints);
    if (n != keypoints.size()) {
        reader.fail("lists " + std::to_string(n) + " keypoints, the keypoint file " + std::to_string(keypoints.size()));
    }
    for (auto& k : keypoints) {
        if (!reader.next(t)) {
            throw FormatError(file, reader.line(),
                              "file ends before all " + std::to_string(n) + " keypoints are listed");
        }
        if (t.size() != 6) {
            reader.fail("expected 6 values (x y scale orientation response laplacian), found " +
                        std::to_string(t.size()));
        }
        if (reader.real_float(t[0], "x") != k.x || reader.real_float(t[1], "y") != k.y) {
            reader.fail(
                fmt::format("position {} {} differs from the keypoint file's {:.9g} {:.9g}", t[0], t[1], k.x, k.y));
        }
        k.scale = reader.real_float(t[2], "scale");
        if (!(k.scale > 0)) reader.fail("scale '" + std::string(t[2]) + "' is not positive");
        k.orientation = reader.real_float(t[3], "orientation");
        k.response = reader.real_float(t[4], "response");
        int laplacian = read_laplacian(reader, t[5]);
        if (has_sign && laplacian != k.laplacian) {
            reader.fail("Laplacian sign differs from the keypoint file's");
        }
        k.laplacian = laplacian;
    }
    if (reader.next(t)) reader.fail("more lines than the " + std::to_string(n) + " keypoints");
}

}  // namespace

std::filesystem::path meta_path(const std::filesystem::path& keypoint_file) {
    std::filesystem::path meta = keypoint_file;
    meta += ".meta";
    return meta;
}

void write_keypoint_file(const std::filesystem::path& file, const surf::Keypoints& keypoints,
                         const KeypointFileOptions& options) {
    for (std::size_t i = 0; i < keypoints.size(); ++i) check_writable(keypoints[i], i);
    write_file_atomically(file, format_keypoints(keypoints, options.laplacian));
    if (options.meta) {
        write_file_atomically(meta_path(file), format_meta(keypoints));
    } else {
        std::filesystem::remove(meta_path(file));  // a stale one would describe other keypoints
    }
}

KeypointFile read_keypoint_file(const std::filesystem::path& file) {
    KeypointFile result;
    TextReader reader(file);
    std::vector<std::string_view> t;
    result.dimension = read_dimension(reader, t);
    std::size_t n = read_header_value(reader, t, "keypoint count", kMaxKeypoints);
    // Not n itself: a 30-byte file may claim 10^8 keypoints (28 GB). A keypoint line has at least
    // 10 bytes ("x y a b c" and its newline), so the file holds no more than its size / 10.
    std::error_code size_error;
    const std::uintmax_t bytes = std::filesystem::file_size(file, size_error);
    result.keypoints.reserve(size_error ? 0 : std::min<std::size_t>(n, bytes / 10));
    for (std::size_t i = 0; i < n; ++i) {
        if (!reader.next(t)) {
            throw FormatError(file, reader.line(),
                              "file ends after " + std::to_string(i) + " of " + std::to_string(n) + " keypoints");
        }
        result.keypoints.push_back(parse_keypoint(reader, t, result.dimension));
    }
    if (reader.next(t)) {
        reader.fail("more keypoint lines than the count " + std::to_string(n) + " on line 2");
    }
    if (std::filesystem::exists(meta_path(file))) {
        apply_meta(meta_path(file), result.keypoints, result.dimension == kDescriptorSize + 1);
        result.meta_read = true;
    }
    return result;
}

}  // namespace surfvp::eval
