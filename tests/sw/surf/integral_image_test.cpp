// Integral image and box sums against brute-force pixel sums (paper eq. 1, OpenSURF clamp).
#include <gtest/gtest.h>

#include <random>

#include <opencv2/core.hpp>

#include "sw/surf/integral_image.h"

namespace surfvp::surf {
namespace {

cv::Mat random_image(int width, int height, unsigned seed) {
    cv::Mat img(height, width, CV_8UC1);
    cv::RNG rng(seed);
    rng.fill(img, cv::RNG::UNIFORM, 0, 256);
    return img;
}

// Sum of the pixels of columns [x0, x1] x rows [y0, y1] that lie inside the image.
int64_t brute_force_sum(const cv::Mat& img, int x0, int y0, int x1, int y1) {
    int64_t sum = 0;
    for (int y = std::max(y0, 0); y <= std::min(y1, img.rows - 1); ++y)
        for (int x = std::max(x0, 0); x <= std::min(x1, img.cols - 1); ++x) sum += img.at<uint8_t>(y, x);
    return sum;
}

TEST(IntegralImage, ValuesAreInclusivePrefixSums) {
    const cv::Mat img = random_image(37, 23, 1);
    const IntegralImage ii(img);
    const IntegralView v = ii.view();
    ASSERT_EQ(v.width, 37);
    ASSERT_EQ(v.height, 23);
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x)
            ASSERT_EQ(v.at(x, y), static_cast<uint32_t>(brute_force_sum(img, 0, 0, x, y))) << x << "," << y;
}

TEST(IntegralImage, BoxSumsInsideMatchBruteForce) {
    const cv::Mat img = random_image(211, 157, 2);
    const IntegralImage ii(img);
    std::mt19937 rng(3);
    for (int n = 0; n < 2000; ++n) {
        const int x0 = std::uniform_int_distribution<int>(1, img.cols - 1)(rng);
        const int y0 = std::uniform_int_distribution<int>(1, img.rows - 1)(rng);
        const int x1 = std::uniform_int_distribution<int>(x0, img.cols - 1)(rng);
        const int y1 = std::uniform_int_distribution<int>(y0, img.rows - 1)(rng);
        ASSERT_EQ(box_sum_inside(ii.view(), x0, y0, x1, y1), brute_force_sum(img, x0, y0, x1, y1));
        ASSERT_EQ(box_sum(ii.view(), x0, y0, x1, y1), brute_force_sum(img, x0, y0, x1, y1));
    }
}

TEST(IntegralImage, ClampedBoxSumsCountOnlyPixelsInsideTheImage) {
    const cv::Mat img = random_image(64, 48, 4);
    const IntegralImage ii(img);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> xs(-80, 140), ys(-60, 110);
    int partly_outside = 0;
    for (int n = 0; n < 5000; ++n) {
        int x0 = xs(rng), x1 = xs(rng), y0 = ys(rng), y1 = ys(rng);
        if (x1 < x0) std::swap(x0, x1);
        if (y1 < y0) std::swap(y0, y1);
        if (x0 < 0 || y0 < 0 || x1 >= img.cols || y1 >= img.rows) ++partly_outside;
        ASSERT_EQ(box_sum(ii.view(), x0, y0, x1, y1), brute_force_sum(img, x0, y0, x1, y1))
            << "box [" << x0 << "," << x1 << "]x[" << y0 << "," << y1 << "]";
    }
    EXPECT_GT(partly_outside, 4000);               // the test really exercises the clamp
    EXPECT_EQ(box_sum(ii.view(), 5, 5, 4, 9), 0);  // empty box
}

TEST(IntegralImage, BoxSumsStayExactWhenCornerValuesWrap) {
    // 4200 x 4200 white pixels sum to 4.5e9 > 2^32: corner values wrap, box sums must not.
    const cv::Mat img(4200, 4200, CV_8UC1, cv::Scalar(255));
    const IntegralImage ii(img);
    EXPECT_EQ(box_sum(ii.view(), 4000, 4100, 4199, 4199), 255LL * 200 * 100);
    EXPECT_EQ(box_sum_inside(ii.view(), 4100, 4100, 4199, 4199), 255 * 100 * 100);
}

}  // namespace
}  // namespace surfvp::surf
