#pragma once
// Synthetic keypoints and scenes for the evaluation tests: the reference SURF is not needed to
// test the measures, only keypoints whose true correspondences are known by construction.
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "sw/surf/keypoint.h"

namespace surfvp::eval::test {

// std::mt19937_64 is specified bit for bit by the standard, its distributions are not: the
// conversions below keep the test data the same on every standard library.
class Random {
public:
    explicit Random(std::uint64_t seed) : engine_(seed) {}

    double uniform(double low, double high) {
        double unit = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
        return low + (high - low) * unit;
    }
    double normal() {  // Box-Muller
        double u = uniform(0, 1), v = uniform(0, 1);
        return std::sqrt(-2.0 * std::log(1.0 - u)) * std::cos(6.283185307179586 * v);
    }
    int sign() { return (engine_() >> 63) ? 1 : -1; }

private:
    std::mt19937_64 engine_;
};

using Descriptor = std::array<float, 64>;

inline Descriptor normalised(const std::array<double, 64>& v) {
    double norm = 0;
    for (double x : v) norm += x * x;
    norm = std::sqrt(norm);
    Descriptor d;
    for (std::size_t i = 0; i < v.size(); ++i) d[i] = static_cast<float>(v[i] / norm);
    return d;
}

// A random direction of the 64-D unit sphere.
inline Descriptor random_descriptor(Random& random) {
    std::array<double, 64> v;
    for (double& x : v) x = random.normal();
    return normalised(v);
}

// `d` moved by a random vector of length `noise`, renormalised.
inline Descriptor perturbed(const Descriptor& d, double noise, Random& random) {
    Descriptor n = random_descriptor(random);
    std::array<double, 64> v;
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = d[i] + noise * n[i];
    return normalised(v);
}

inline surf::Keypoint random_keypoint(Random& random, double width, double height, double min_scale = 1.2,
                                      double max_scale = 6.0) {
    surf::Keypoint k;
    k.x = static_cast<float>(random.uniform(0, width));
    k.y = static_cast<float>(random.uniform(0, height));
    k.scale = static_cast<float>(random.uniform(min_scale, max_scale));
    k.orientation = static_cast<float>(random.uniform(-3.14159, 3.14159));
    k.response = static_cast<float>(random.uniform(100, 50000));
    k.laplacian = random.sign();
    k.descriptor = random_descriptor(random);
    return k;
}

inline surf::Keypoints random_keypoints(Random& random, std::size_t n, double width, double height,
                                        double min_scale = 1.2, double max_scale = 6.0) {
    surf::Keypoints keypoints;
    for (std::size_t i = 0; i < n; ++i) {
        keypoints.push_back(random_keypoint(random, width, height, min_scale, max_scale));
    }
    return keypoints;
}

// Package data is a hard requirement: a missing file fails the test and names the package.
inline ::testing::AssertionResult package_file(const std::filesystem::path& file, const char* package) {
    if (std::filesystem::exists(file)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << file << " is missing: install the Debian package " << package
                                         << " (apt-get install " << package << ")";
}

// A fresh folder for one test, removed afterwards.
class TemporaryFolder {
public:
    TemporaryFolder() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() / ("surfvp-eval-" + std::string(info->test_suite_name()) + "-" +
                                                          info->name() + "-" + std::to_string(::getpid()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TemporaryFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

}  // namespace surfvp::eval::test
