// sw/surf's orientation, descriptor, Haar wavelets and hessian_at on a MemoryView over a
// big-endian copy of the integral image give bit-identical results to the native
// IntegralView, and every read goes through the probe with an address inside the buffer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "models/common/byte_order.h"
#include "stage_fixture.h"
#include "sw/surf/descriptor.h"
#include "sw/surf/fast_hessian.h"
#include "sw/surf/haar.h"
#include "sw/surf/memory_view.h"
#include "sw/surf/orientation.h"
#include "sw/surf/surf.h"

namespace surfvp::stage_test {
namespace {

constexpr uint32_t kBase = 0x10000000;

struct Reads {
    uint64_t count = 0;
    uint32_t lowest = ~0u, highest = 0;
    bool aligned = true;
};

struct RecordingProbe {
    Reads* reads;
    void load(uint32_t address, unsigned bytes) const {
        ++reads->count;
        reads->lowest = std::min(reads->lowest, address);
        reads->highest = std::max(reads->highest, address + bytes);
        reads->aligned = reads->aligned && address % 4 == 0 && bytes == 4;
    }
};

// The integral image of `gray` natively and as big-endian words with a padded stride (rows
// need not be packed in memory).
struct TwoViews {
    surf::IntegralImage native;
    std::vector<uint8_t> bytes;
    size_t stride = 0;

    explicit TwoViews(const cv::Mat& gray) : native(gray) {
        const surf::IntegralView v = native.view();
        stride = size_t(v.width) * 4 + 64;
        bytes.assign(stride * size_t(v.height), 0xAB);
        for (int y = 0; y < v.height; ++y)
            for (int x = 0; x < v.width; ++x) store_be32(&bytes[size_t(y) * stride + size_t(x) * 4], v.at(x, y));
    }
    template <class Probe>
    surf::MemoryView<Probe> memory(Probe probe) const {
        const surf::IntegralView v = native.view();
        return {bytes.data(), kBase, v.width, v.height, stride, probe};
    }
};

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Keypoints of the reference on graf1, plus hand-placed ones at and beyond the borders (the
// clamped read path) and at large scales.
surf::Keypoints test_keypoints(const cv::Mat& gray) {
    surf::Params p;
    p.octaves = 2;
    p.threshold = 300;
    surf::Keypoints kps = surf::detect(gray, p);
    for (float s : {1.6f, 2.8f, 6.8f})
        for (float x : {0.0f, 3.3f, float(gray.cols) - 1.5f})
            for (float y : {-2.0f, 5.7f, float(gray.rows) - 0.2f}) {
                surf::Keypoint k;
                k.x = x;
                k.y = y;
                k.scale = s;
                k.orientation = 0.7f * s;
                kps.push_back(k);
            }
    return kps;
}

TEST(MemoryView, OrientationAndDescriptorAreBitIdentical) {
    const cv::Mat gray = graf1_1024x768();
    ASSERT_FALSE(gray.empty());
    const TwoViews views(gray);
    const surf::IntegralView native = views.native.view();
    Reads reads;
    const auto memory = views.memory(RecordingProbe{&reads});
    const surf::Keypoints kps = test_keypoints(gray);
    ASSERT_GT(kps.size(), 100u);
    for (surf::Keypoint kp : kps) {
        const float a = surf::orientation(native, kp.x, kp.y, kp.scale);
        const float b = surf::orientation(memory, kp.x, kp.y, kp.scale);
        ASSERT_TRUE(same_bits(a, b)) << kp.x << "," << kp.y << ": " << a << " vs " << b;
        kp.orientation = a;
        const std::array<float, 64> da = surf::descriptor(native, kp);
        const std::array<float, 64> db = surf::descriptor(memory, kp);
        ASSERT_EQ(std::memcmp(da.data(), db.data(), sizeof(float) * 64), 0) << kp.x << "," << kp.y;
    }
    EXPECT_TRUE(reads.aligned);
    EXPECT_GE(reads.lowest, kBase);
    EXPECT_LE(reads.highest, kBase + views.stride * size_t(native.height));
}

TEST(MemoryView, HaarBoxAndHessianAreBitIdentical) {
    const cv::Mat gray = graf1_1024x768();
    ASSERT_FALSE(gray.empty());
    const TwoViews views(gray);
    const surf::IntegralView native = views.native.view();
    const auto memory = views.memory(surf::NoProbe{});
    for (int i = 0; i < 2000; ++i) {
        const float x = float((i * 7919) % 1100) - 30.5f + 0.37f * float(i % 3);
        const float y = float((i * 104729) % 820) - 25.25f;
        const float size = 2.0f + float(i % 23) * 0.8f;
        const surf::HaarResponse a = surf::haar_response(native, x, y, size);
        const surf::HaarResponse b = surf::haar_response(memory, x, y, size);
        ASSERT_TRUE(same_bits(a.dx, b.dx) && same_bits(a.dy, b.dy)) << x << "," << y << " size " << size;
        const int x0 = int(x), y0 = int(y);
        ASSERT_EQ(surf::box_sum(native, x0, y0, x0 + 17, y0 + 9), surf::box_sum(memory, x0, y0, x0 + 17, y0 + 9));
        ASSERT_EQ(surf::area_integral(native, x, y), surf::area_integral(memory, x, y));
    }
    for (int L : {9, 15, 21, 27, 39, 51})
        for (int y = 30; y < 740; y += 37)
            for (int x = 30; x < 990; x += 41) {
                const surf::Hessian a = surf::hessian_at(native, x, y, L);
                const surf::Hessian b = surf::hessian_at(memory, x, y, L);
                ASSERT_TRUE(a.dxx == b.dxx && a.dyy == b.dyy && a.dxy == b.dxy && same_bits(a.det, b.det) &&
                            a.laplacian == b.laplacian);
            }
}

// 32 reads per Haar wavelet inside the image: 109 x 32 for an orientation, 400 x 32 for a
// descriptor, 32 for hessian_at (what the cost model is told).
TEST(MemoryView, ProbeSeesEveryReadOfTheReferenceCode) {
    const cv::Mat gray = graf1_1024x768();
    ASSERT_FALSE(gray.empty());
    const TwoViews views(gray);
    Reads reads;
    const auto memory = views.memory(RecordingProbe{&reads});
    surf::orientation(memory, 500.3f, 400.6f, 2.4f);
    EXPECT_EQ(reads.count, 109u * 32);
    reads = {};
    surf::Keypoint kp;
    kp.x = 500.3f;
    kp.y = 400.6f;
    kp.scale = 2.4f;
    kp.orientation = 1.0f;
    surf::descriptor(memory, kp);
    EXPECT_EQ(reads.count, 400u * 32);
    reads = {};
    surf::hessian_at(memory, 500, 400, 27);
    EXPECT_EQ(reads.count, 32u);
    reads = {};
    surf::orientation(memory, -40.0f, -40.0f, 2.0f);  // far outside: negative coordinates read nothing
    EXPECT_EQ(reads.count, 0u);
}

// The same in HaarMode::rounded: bit-identical on both views, 8 reads per wavelet pair inside
// the image (109 x 8 for an orientation, 400 x 8 for a descriptor).
TEST(MemoryView, RoundedOrientationAndDescriptorAreBitIdentical) {
    const cv::Mat gray = graf1_1024x768();
    ASSERT_FALSE(gray.empty());
    const TwoViews views(gray);
    const surf::IntegralView native = views.native.view();
    Reads reads;
    const auto memory = views.memory(RecordingProbe{&reads});
    const surf::Keypoints kps = test_keypoints(gray);
    ASSERT_GT(kps.size(), 100u);
    constexpr auto rounded = surf::HaarMode::rounded;
    for (surf::Keypoint kp : kps) {
        const float a = surf::orientation(native, kp.x, kp.y, kp.scale, rounded);
        const float b = surf::orientation(memory, kp.x, kp.y, kp.scale, rounded);
        ASSERT_TRUE(same_bits(a, b)) << kp.x << "," << kp.y << ": " << a << " vs " << b;
        kp.orientation = a;
        const std::array<float, 64> da = surf::descriptor(native, kp, rounded);
        const std::array<float, 64> db = surf::descriptor(memory, kp, rounded);
        ASSERT_EQ(std::memcmp(da.data(), db.data(), sizeof(float) * 64), 0) << kp.x << "," << kp.y;
    }
    EXPECT_TRUE(reads.aligned);
    EXPECT_GE(reads.lowest, kBase);
    EXPECT_LE(reads.highest, kBase + views.stride * size_t(native.height));
    for (int i = 0; i < 2000; ++i) {
        const float x = float((i * 7919) % 1100) - 30.5f + 0.37f * float(i % 3);
        const float y = float((i * 104729) % 820) - 25.25f;
        const int half = 1 + i % 17;
        const surf::HaarResponse p = surf::haar_response_rounded(native, x, y, half);
        const surf::HaarResponse q = surf::haar_response_rounded(views.memory(surf::NoProbe{}), x, y, half);
        ASSERT_TRUE(same_bits(p.dx, q.dx) && same_bits(p.dy, q.dy)) << x << "," << y << " half " << half;
    }

    reads = {};
    surf::orientation(memory, 500.3f, 400.6f, 2.4f, rounded);
    EXPECT_EQ(reads.count, 109u * 8);
    reads = {};
    surf::Keypoint kp;
    kp.x = 500.3f;
    kp.y = 400.6f;
    kp.scale = 2.4f;
    kp.orientation = 1.0f;
    surf::descriptor(memory, kp, rounded);
    EXPECT_EQ(reads.count, 400u * 8);
    reads = {};
    surf::orientation(memory, -40.0f, -40.0f, 2.0f, rounded);  // far outside: nothing read
    EXPECT_EQ(reads.count, 0u);
}

}  // namespace
}  // namespace surfvp::stage_test
