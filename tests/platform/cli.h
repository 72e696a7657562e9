#pragma once
// Runs the surfvp binary as a user would, capturing exit code, stdout and stderr.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include <gtest/gtest.h>

namespace surfvp::test {

struct Cli {
    int exit_code;
    std::string out;
    std::string err;
};

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

inline Cli surfvp(const std::string& args) {
    const auto dir = std::filesystem::temp_directory_path();
    const std::string tag = std::to_string(::getpid());
    const std::string out = (dir / ("surfvp_out_" + tag)).string(), err = (dir / ("surfvp_err_" + tag)).string();
    const std::string command = std::string(SURFVP_BINARY) + " " + args + " >" + out + " 2>" + err;
    const int status = std::system(command.c_str());
    Cli result{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return result;
}

// The default scenario, and the settings that make it one run (it asks for its verdict's
// re-simulations).
inline const std::string kBudget = std::string(SURFVP_SOURCE_DIR) + "/scenarios/budget_1024x768.yaml";
inline const std::string kOneRun = " --set verdict.band=off --set verdict.break_even=off --set verdict.software=off";
// A device two accelerator pairs fit (80,000 LUTs, 228 RAMB36), for tests of two pairs whose
// point is not the fit: on the FX70T they miss their goal (docs/resources.md).
inline const std::string kRoomForTwoPairs = " --set fpga.slices=20000 --set fpga.ramb36=228";

// This test process's folder under the temporary directory. It is emptied when first used,
// because a process id comes back: a folder an earlier process of the same id left would
// otherwise pass for this one's output. It is removed at exit if every test passed, and kept
// for a look otherwise.
inline const std::filesystem::path& test_root() {
    struct Root {
        std::filesystem::path path =
            std::filesystem::temp_directory_path() / ("surfvp_test_" + std::to_string(::getpid()));
        Root() { std::filesystem::remove_all(path); }
        ~Root() {
            std::error_code ignored;
            if (::testing::UnitTest::GetInstance()->Passed()) std::filesystem::remove_all(path, ignored);
        }
    };
    static const Root root;
    return root.path;
}

// The folder fresh_dir(name) makes, without emptying it.
inline std::string fresh_path(const std::string& name) { return (test_root() / name).string(); }

// A fresh empty folder under the temporary directory, unique to this test process.
inline std::string fresh_dir(const std::string& name) {
    const std::filesystem::path dir = fresh_path(name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

inline std::string write_file(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = (std::filesystem::path(dir) / name).string();
    std::ofstream(path) << text;
    return path;
}

// Test data of Debian packages: a missing file fails the test with the package's name.
inline const std::string kOpencvData = OPENCV_DATA_DIR;
// graf<n>.png of opencv-doc's data.
inline std::string graf(int n) { return kOpencvData + "/graf" + std::to_string(n) + ".png"; }
inline const std::string kCastle = std::string(VISP_DATA_DIR) + "/mbt-depth/Castle-simu";

inline ::testing::AssertionResult have_data(const std::string& path, const std::string& package) {
    if (std::filesystem::exists(path)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << path << " is missing: install the Debian package " << package
                                         << " (apt-get install " << package << ")";
}
#define REQUIRE_OPENCV_DATA(name) ASSERT_TRUE(test::have_data(test::kOpencvData + "/" + (name), "opencv-doc"))
#define REQUIRE_CASTLE() ASSERT_TRUE(test::have_data(test::kCastle + "/Images/Image_0001.pgm", "visp-images-data"))

}  // namespace surfvp::test
