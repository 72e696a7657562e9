#pragma once
// Image and video files through OpenCV's imgcodecs and videoio, which surfvp does not link:
// with their dependencies (GDAL, GStreamer, FFmpeg, ...) they are ~240 shared libraries, whose
// loading alone took ~0.2 s of every start. They live in a plugin, libsurfvp_media.so, loaded
// on the first call here (a run whose frames come from the frame cache never loads it).
//
// Decoded images and encoded ones are kept in the cache folder (models/host/disk_cache.h):
// a decoded image under its file's real path, size, modification time and the flags; an
// encoded one under the extension and two hashes of the image's bytes. Videos are not cached.
//
// The plugin is looked for in $SURFVP_MEDIA_PLUGIN, next to the running executable, then where
// the build put it. One that cannot be loaded throws MediaError naming the path and the loader's
// message. The calls behave as the OpenCV functions they forward to; flags are cv::IMREAD_*.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace surfvp::media {

struct MediaError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

cv::Mat read_image(const std::string& path, int flags);  // cv::imread: empty when not decoded
// cv::imencode: false when the extension names no encoder or the image cannot be encoded.
bool encode_image(const std::string& extension, const cv::Mat& image, std::vector<unsigned char>& bytes);

// An image's shape and two independent 64-bit hashes of its bytes, as one line: a cache key for
// what is computed from it.
std::string content_key(const cv::Mat& image);

// cv::VideoCapture on a file, read front to back.
class Video {
public:
    explicit Video(const std::string& path);
    ~Video();
    Video(const Video&) = delete;
    Video& operator=(const Video&) = delete;

    bool opened() const { return handle_ != nullptr; }
    bool grab();                // skips a frame; false after the last
    bool read(cv::Mat& frame);  // the next frame as decoded (BGR); false after the last

private:
    void* handle_;
};

}  // namespace surfvp::media
