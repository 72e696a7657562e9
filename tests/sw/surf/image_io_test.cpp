// Every bad input gives an ImageError whose message names the file and the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sw/surf/image_io.h"
#include "sw/surf/surf.h"
#include "tests/sw/surf/test_data.h"

namespace surfvp::surf {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test under the system temp dir.
class ImageIo : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("surfvp_image_io_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    fs::path dir_;
};

// Runs `f`, which must throw ImageError with every word of `words` in its message.
template <typename F>
void expect_image_error(F f, const std::vector<std::string>& words) {
    try {
        f();
        ADD_FAILURE() << "no ImageError";
    } catch (const ImageError& e) {
        const std::string message = e.what();
        for (const std::string& w : words)
            EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' not in: " << message;
    }
}

TEST_F(ImageIo, MissingFile) {
    const std::string p = path("nothing_here.png");
    expect_image_error([&] { load_gray(p); }, {p, "does not exist"});
}

TEST_F(ImageIo, Directory) {
    expect_image_error([&] { load_gray(dir_.string()); }, {dir_.string(), "directory"});
}

TEST_F(ImageIo, EmptyFile) {
    const std::string p = path("empty.png");
    std::ofstream(p).close();
    expect_image_error([&] { load_gray(p); }, {p, "empty", "0 bytes"});
}

TEST_F(ImageIo, NotAnImage) {
    const std::string p = path("text.png");
    std::ofstream(p) << "this is not a PNG file\n";
    expect_image_error([&] { load_gray(p); }, {p, "not an image"});
}

TEST_F(ImageIo, TooSmallForTheFirstOctave) {
    // The paper's 4 intervals: the largest filter of octave 0 is 27, so the minimum side is
    // 27+1+2 = 30; the default 5 intervals: 33+1+2 = 36.
    EXPECT_EQ(minimum_image_side(paper_surf()), 30);
    EXPECT_EQ(minimum_image_side(Params{}), 36);
    const std::string p = path("small.png");
    ASSERT_TRUE(cv::imwrite(p, cv::Mat(100, 29, CV_8UC1, cv::Scalar(7))));
    expect_image_error([&] { load_gray(p, paper_surf()); }, {p, "too small", "100", "29", "27", "30x30"});
    ASSERT_TRUE(cv::imwrite(p, cv::Mat(100, 35, CV_8UC1, cv::Scalar(7))));
    expect_image_error([&] { load_gray(p); }, {p, "too small", "100", "35", "33", "36x36"});

    const std::string ok = path("ok.png");
    ASSERT_TRUE(cv::imwrite(ok, cv::Mat(30, 30, CV_8UC1, cv::Scalar(7))));
    EXPECT_EQ(load_gray(ok, paper_surf()).size(), cv::Size(30, 30));
}

TEST_F(ImageIo, ColourFilesAreConvertedToGrey) {
    const std::string p = path("colour.png");
    ASSERT_TRUE(cv::imwrite(p, cv::Mat(40, 50, CV_8UC3, cv::Scalar(10, 20, 30))));
    const cv::Mat g = load_gray(p);
    EXPECT_EQ(g.type(), CV_8UC1);
    EXPECT_EQ(g.size(), cv::Size(50, 40));
}

TEST_F(ImageIo, LoadsTheOpenCvExample) {
    const std::string p = test::opencv_data("graf1.png");
    ASSERT_FALSE(p.empty());
    EXPECT_EQ(load_gray(p).size(), cv::Size(800, 640));
}

TEST(ImageChecks, InMemoryImagesAreCheckedByEveryEntryPoint) {
    Params params = paper_surf();
    expect_image_error([&] { detect(cv::Mat(), params); }, {"image", "empty"});
    expect_image_error([&] { detect(cv::Mat(64, 64, CV_8UC3), params); }, {"image", "8-bit single-channel"});
    expect_image_error([&] { detect(cv::Mat(64, 64, CV_16UC1), params); }, {"image", "8-bit single-channel"});
    const cv::Mat small(31, 200, CV_8UC1, cv::Scalar(0));  // 31 < 27 + 1 + 2 * 2 with init_step 2
    params.init_step = 2;
    expect_image_error([&] { detect_and_describe(small, params); }, {"image", "too small", "32x32"});
    expect_image_error([&] { threshold_for_count(small, 10, params); }, {"too small"});
    Keypoints none;
    expect_image_error([&] { describe(small, none, params); }, {"too small"});
}

}  // namespace
}  // namespace surfvp::surf
