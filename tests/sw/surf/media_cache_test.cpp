// Images through the codec plugin and the cache folder (sw/media/media.h), and the threshold
// calibration's stored responses (surf.h, stored_ranked_responses): what comes back from the
// cache is what the decoder and the detector give, the cache file is really read, and a
// changed file is decoded again.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>

#include "models/host/disk_cache.h"
#include "sw/media/media.h"
#include "sw/surf/surf.h"
#include "tests/sw/surf/test_data.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;

// A fresh cache folder for this test process (each test runs in its own process).
fs::path fresh_cache(const char* name) {
    const fs::path dir = fs::temp_directory_path() / fmt::format("surfvp_media_{}_{}", name, ::getpid());
    fs::remove_all(dir);
    ::setenv("SURFVP_CACHE", dir.c_str(), 1);
    return dir;
}

size_t entries(const fs::path& dir, const std::string& kind) {
    size_t n = 0;
    if (!fs::exists(dir)) return 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().rfind(kind + "-", 0) == 0;
    return n;
}

// Changes an entry's data; `reseal` writes it as the cache would (a new checksum), else only the
// bytes change, as a flipped bit or a foreign writer would.
void doctor(const fs::path& entry, const std::function<void(std::string&)>& change, bool reseal) {
    std::ifstream in(entry, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    const size_t key_end = text.find('\n'), seal_end = text.find('\n', key_end + 1);
    std::string data = text.substr(seal_end + 1);
    change(data);
    std::ofstream(entry, std::ios::binary | std::ios::trunc)
        << (reseal ? cache_entry(text.substr(0, key_end), data) : text.substr(0, seal_end + 1) + data);
}

TEST(MediaCache, ADecodedImageIsKeptAndReadBackAsDecoded) {
    const fs::path cache = fresh_cache("image");
    const std::string graf = surf::test::opencv_data("graf1.png");
    ASSERT_FALSE(graf.empty());
    const cv::Mat decoded = media::read_image(graf, cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(decoded.size(), cv::Size(800, 640));
    EXPECT_EQ(cv::norm(decoded, cv::imread(graf, cv::IMREAD_GRAYSCALE), cv::NORM_INF), 0);  // as OpenCV decodes it
    EXPECT_EQ(entries(cache, "image"), 1u);
    const cv::Mat again = media::read_image(graf, cv::IMREAD_GRAYSCALE);
    EXPECT_EQ(cv::norm(decoded, again, cv::NORM_INF), 0);
    EXPECT_EQ(entries(cache, "image"), 1u);
    // Colour is another entry.
    EXPECT_EQ(media::read_image(graf, cv::IMREAD_COLOR).channels(), 3);
    EXPECT_EQ(entries(cache, "image"), 2u);
}

TEST(MediaCache, TheCacheFileIsReadAndAChangedImageIsDecodedAgain) {
    const fs::path cache = fresh_cache("changed");
    const fs::path image = cache.parent_path() / fmt::format("surfvp_media_image_{}.png", ::getpid());
    ASSERT_TRUE(cv::imwrite(image.string(), cv::Mat(40, 50, CV_8UC1, cv::Scalar(10))));
    EXPECT_EQ(media::read_image(image.string(), cv::IMREAD_GRAYSCALE).at<uchar>(0, 0), 10);
    // Doctor the entry: the next read returns it, so the cache is really used.
    ASSERT_EQ(entries(cache, "image"), 1u);
    const fs::path entry = fs::directory_iterator(cache)->path();
    doctor(
        entry, [](std::string& data) { data.back() = char(77); }, false);  // the last pixel, checksum left
    EXPECT_EQ(media::read_image(image.string(), cv::IMREAD_GRAYSCALE).at<uchar>(39, 49), 10);  // a miss, decoded again
    doctor(
        entry, [](std::string& data) { data.back() = char(77); }, true);
    EXPECT_EQ(media::read_image(image.string(), cv::IMREAD_GRAYSCALE).at<uchar>(39, 49), 77);
    // A new file under the same name (another size, a later time) is decoded again.
    ASSERT_TRUE(cv::imwrite(image.string(), cv::Mat(30, 50, CV_8UC1, cv::Scalar(20))));
    fs::last_write_time(image, fs::last_write_time(image) + std::chrono::seconds(2));
    const cv::Mat fresh = media::read_image(image.string(), cv::IMREAD_GRAYSCALE);
    EXPECT_EQ(fresh.rows, 30);
    EXPECT_EQ(fresh.at<uchar>(29, 49), 20);
    // A cut entry is a miss, not garbage.
    for (const auto& e : fs::directory_iterator(cache)) fs::resize_file(e.path(), 40);
    EXPECT_EQ(media::read_image(image.string(), cv::IMREAD_GRAYSCALE).at<uchar>(29, 49), 20);
    fs::remove(image);
}

TEST(MediaCache, OffKeepsNothing) {
    const fs::path cache = fresh_cache("off");
    ::setenv("SURFVP_CACHE", "off", 1);
    const std::string graf = surf::test::opencv_data("graf1.png");
    ASSERT_FALSE(graf.empty());
    EXPECT_FALSE(media::read_image(graf, cv::IMREAD_GRAYSCALE).empty());
    EXPECT_FALSE(fs::exists(cache));
    EXPECT_FALSE(cache_folder().has_value());
}

TEST(MediaCache, EncodedImagesAreKeptByContent) {
    const fs::path cache = fresh_cache("encoded");
    cv::Mat a(20, 30, CV_8UC1, cv::Scalar(5)), b = a.clone();
    b.at<uchar>(19, 29) = 6;
    std::vector<unsigned char> pa, pa2, pb;
    ASSERT_TRUE(media::encode_image(".png", a, pa));
    ASSERT_TRUE(media::encode_image(".png", a, pa2));
    ASSERT_TRUE(media::encode_image(".png", b, pb));
    EXPECT_EQ(pa, pa2);
    EXPECT_NE(pa, pb);  // one pixel apart: another entry
    EXPECT_EQ(entries(cache, "encoded"), 2u);
    EXPECT_EQ(cv::norm(cv::imdecode(pb, cv::IMREAD_GRAYSCALE), b, cv::NORM_INF), 0);
    std::vector<unsigned char> none;
    EXPECT_FALSE(media::encode_image(".nothing", a, none));
}

TEST(MediaCache, StoredResponsesAreTheDetectorsAndAreRead) {
    const fs::path cache = fresh_cache("ranked");
    const cv::Mat graf = surf::test::opencv_gray("graf1.png");
    ASSERT_FALSE(graf.empty());
    surf::Params p = surf::paper_surf();
    p.octaves = 2;
    const std::vector<float> ranked = surf::ranked_responses(graf, p);
    ASSERT_GT(ranked.size(), 1000u);
    EXPECT_EQ(surf::stored_ranked_responses(graf, p), ranked);
    ASSERT_EQ(entries(cache, "ranked"), 1u);
    EXPECT_EQ(surf::stored_ranked_responses(graf, p), ranked);  // from the file
    // Another image, other parameters: other entries.
    p.max_offset = 1;
    const std::vector<float> other = surf::ranked_responses(graf, p);
    EXPECT_EQ(surf::stored_ranked_responses(graf, p), other);
    EXPECT_EQ(entries(cache, "ranked"), 2u);
    // Doctored: the file is what is read.
    auto last_to = [](float value) {
        return [value](std::string& data) {
            std::memcpy(data.data() + data.size() - sizeof(float), &value, sizeof(float));
        };
    };
    for (const auto& e : fs::directory_iterator(cache)) doctor(e.path(), last_to(12345.0f), false);
    EXPECT_EQ(surf::stored_ranked_responses(graf, p), other);  // flipped bytes: a miss, computed again
    for (const auto& e : fs::directory_iterator(cache)) doctor(e.path(), last_to(12345.0f), true);
    EXPECT_EQ(surf::stored_ranked_responses(graf, p).back(), 12345.0f);
}

// Without the plugin, the first image read fails with a message that names it.
TEST(MediaCache, AMissingPluginIsNamed) {
    fresh_cache("plugin");
    ::setenv("SURFVP_MEDIA_PLUGIN", "/nonexistent/libsurfvp_media.so", 1);
    try {
        media::read_image(surf::test::opencv_data("graf1.png"), cv::IMREAD_GRAYSCALE);
        ADD_FAILURE() << "no MediaError";
    } catch (const media::MediaError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/libsurfvp_media.so"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("SURFVP_MEDIA_PLUGIN"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace surfvp
