#include "sw/media/media.h"

#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <fmt/format.h>

#include "sw/media/plugin_abi.h"

namespace surfvp::media {
namespace {
namespace fs = std::filesystem;

struct Plugin {
    decltype(&surfvp_media_read_image) read_image;
    decltype(&surfvp_media_encode_image) encode_image;
    decltype(&surfvp_media_video_open) video_open;
    decltype(&surfvp_media_video_grab) video_grab;
    decltype(&surfvp_media_video_read) video_read;
    decltype(&surfvp_media_video_close) video_close;
};

constexpr const char* kFileName = "libsurfvp_media.so";

// $SURFVP_MEDIA_PLUGIN, else beside the executable, else where the build put it.
fs::path plugin_path() {
    if (const char* env = std::getenv("SURFVP_MEDIA_PLUGIN"); env && *env) return env;
    std::error_code ec;
    const fs::path beside = fs::read_symlink("/proc/self/exe", ec).parent_path() / kFileName;
    if (!ec && fs::exists(beside)) return beside;
    return SURFVP_MEDIA_PLUGIN;
}

template <class F>
void bind(void* handle, const fs::path& path, const char* name, F& f) {
    f = reinterpret_cast<F>(dlsym(handle, name));
    if (!f) throw MediaError(fmt::format("{}: the image and video plugin lacks {}", path.string(), name));
}

Plugin load() {
    const fs::path path = plugin_path();
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle)
        throw MediaError(fmt::format("cannot load the image and video plugin {}: {} (set SURFVP_MEDIA_PLUGIN to its path)",
                                     path.string(), dlerror()));
    Plugin p{};  // never closed: OpenCV's codec libraries keep state until the process ends
    bind(handle, path, "surfvp_media_read_image", p.read_image);
    bind(handle, path, "surfvp_media_encode_image", p.encode_image);
    bind(handle, path, "surfvp_media_video_open", p.video_open);
    bind(handle, path, "surfvp_media_video_grab", p.video_grab);
    bind(handle, path, "surfvp_media_video_read", p.video_read);
    bind(handle, path, "surfvp_media_video_close", p.video_close);
    return p;
}

const Plugin& plugin() {
    static const Plugin p = load();  // C++11: initialised once, also across threads
    return p;
}

}  // namespace

cv::Mat read_image(const std::string& path, int flags) {
    cv::Mat image;
    plugin().read_image(&path, flags, &image);
    return image;
}

bool encode_image(const std::string& extension, const cv::Mat& image, std::vector<unsigned char>& bytes) {
    return plugin().encode_image(&extension, &image, &bytes);
}

Video::Video(const std::string& path) : handle_(plugin().video_open(&path)) {}

Video::~Video() {
    if (handle_) plugin().video_close(handle_);
}

bool Video::grab() { return handle_ && plugin().video_grab(handle_); }

bool Video::read(cv::Mat& frame) { return handle_ && plugin().video_read(handle_, &frame); }

}  // namespace surfvp::media
