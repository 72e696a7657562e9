// IntegralCore against OpenCV's cv::integral, bit for bit.
#include <opencv2/imgproc.hpp>
#include <vector>

#include "models/iig/integral_core.h"
#include "test_images.h"

namespace surfvp {
namespace {

// cv::integral has a zero first row and column; the IIG's inclusive image is the rest.
void expect_matches_opencv(const cv::Mat& image, unsigned bits = 28) {
    ASSERT_FALSE(image.empty());
    const auto ours = IntegralCore(bits).image(image.data, image.cols, image.rows, image.step);
    ASSERT_TRUE(ours.has_value());
    cv::Mat reference;
    cv::integral(image, reference, CV_32S);
    for (int y = 0; y < image.rows; ++y)
        for (int x = 0; x < image.cols; ++x)
            ASSERT_EQ((*ours)[size_t(y) * image.cols + x], uint32_t(reference.at<int32_t>(y + 1, x + 1)))
                << "at " << x << "," << y;
}

TEST(IntegralCore, BitExactWithOpenCvOnRealImages) {
    for (const char* name : {"graf1.png", "graf3.png", "leuvenA.jpg"}) expect_matches_opencv(test::real_image(name));
}

TEST(IntegralCore, BitExactWithOpenCvOnRandomImages) {
    expect_matches_opencv(test::random_image(1024, 768, 1));
    expect_matches_opencv(test::random_image(37, 53, 2));  // odd sizes
    expect_matches_opencv(test::random_image(1, 1, 3));
}

TEST(IntegralCore, WhiteMaximumImageFitsIn28Bits) {
    const cv::Mat white(1024, 1024, CV_8UC1, cv::Scalar(255));
    expect_matches_opencv(white, 28);
    const auto ours = IntegralCore(28).image(white.data, 1024, 1024, white.step);
    EXPECT_EQ(ours->back(), 255u * 1024 * 1024);  // 267,386,880 < 2^28
}

TEST(IntegralCore, SumsBeyondTheWidthAreAnErrorNotAWrap) {
    const cv::Mat white(1024, 1024, CV_8UC1, cv::Scalar(255));
    EXPECT_FALSE(IntegralCore(27).image(white.data, 1024, 1024, white.step).has_value());
    const cv::Mat small(16, 16, CV_8UC1, cv::Scalar(255));  // 65,280 < 2^16
    EXPECT_TRUE(IntegralCore(16).image(small.data, 16, 16, small.step).has_value());
    const cv::Mat over(17, 16, CV_8UC1, cv::Scalar(255));  // 69,360 >= 2^16
    EXPECT_FALSE(IntegralCore(16).image(over.data, 16, 17, over.step).has_value());
}

// A row stops at its first value that does not fit, as the adder chain does: the values before
// it are written, the rest of `out` is left; a row whose last value is one below the limit fits.
TEST(IntegralCore, ARowStopsAtItsFirstValueThatDoesNotFit) {
    const IntegralCore core(16);
    const std::vector<uint8_t> pixels(40, 255);
    const std::vector<uint32_t> above(40, 64000);  // 255 (x + 1) + 64000 >= 65536 from x = 6 on
    std::vector<uint32_t> out(40, 0xDEADBEEF);
    EXPECT_FALSE(core.row(pixels.data(), above.data(), out.data(), 40));
    for (uint32_t x = 0; x < 6; ++x) EXPECT_EQ(out[x], 255 * (x + 1) + 64000) << x;
    for (uint32_t x = 6; x < 40; ++x) EXPECT_EQ(out[x], 0xDEADBEEFu) << x;
    const std::vector<uint32_t> just(40, 65535 - 255 * 40);  // the last value is 65535
    EXPECT_TRUE(core.row(pixels.data(), just.data(), out.data(), 40));
    EXPECT_EQ(out[39], 65535u);
    EXPECT_EQ(out[0], 65535u - 255 * 39);
    const std::vector<uint32_t> over(40, 65536 - 255 * 40);  // the last value is the limit
    EXPECT_FALSE(core.row(pixels.data(), over.data(), out.data(), 40));
    EXPECT_EQ(out[38], 65536u - 255);  // written: it fits
    EXPECT_EQ(out[39], 65535u);        // left from the row before
}

TEST(IntegralCore, RejectsImpossibleWidths) {
    EXPECT_THROW(IntegralCore(7), std::invalid_argument);
    EXPECT_THROW(IntegralCore(33), std::invalid_argument);
}

}  // namespace
}  // namespace surfvp
