#include "sw/media/media.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <elf.h>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string_view>
#include <sys/statvfs.h>

#include "models/host/disk_cache.h"
#include "models/common/zeroed_memory.h"
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

// The loader maps a shared object's segments as its headers say; a segment past the file's end
// (a truncated copy) is mapped all the same and faults (SIGBUS) when first touched. So the
// headers are checked against the file before it is handed to dlopen.
std::string elf_problem(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return "not a readable regular file";  // before opening: a FIFO would block
    std::ifstream in(path, std::ios::binary);
    const uintmax_t size = fs::file_size(path, ec);
    if (!in || ec) return "not a readable regular file";
    Elf64_Ehdr header{};
    if (!in.read(reinterpret_cast<char*>(&header), sizeof header) ||
        std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64 ||
        header.e_phentsize != sizeof(Elf64_Phdr))
        return "not a 64-bit ELF shared object";
    // Each bound as `offset > size - length`: a hostile offset near 2^64 must not wrap past the check.
    const auto beyond = [size](uint64_t offset, uint64_t length) { return length > size || offset > size - length; };
    if (beyond(header.e_phoff, uintmax_t(header.e_phnum) * sizeof(Elf64_Phdr))) return "cut short (program headers)";
    if (beyond(header.e_shoff, uintmax_t(header.e_shnum) * header.e_shentsize)) return "cut short (section headers)";
    in.seekg(std::streamoff(header.e_phoff));
    for (unsigned i = 0; i < header.e_phnum; ++i) {
        Elf64_Phdr segment{};
        if (!in.read(reinterpret_cast<char*>(&segment), sizeof segment)) return "cut short (program headers)";
        if (segment.p_type == PT_LOAD && beyond(segment.p_offset, segment.p_filesz))
            return fmt::format("cut short: segment {} ends at byte {}, the file at {}", i,
                               segment.p_offset + segment.p_filesz, size);
    }
    return "";
}

// The loader's words when mmap failed, without its errno: out of memory (or address space),
// unless the file system forbids executing what is on it.
bool mapping_refused(const std::string& why, const fs::path& path) {
    const bool mapping = why.find("failed to map segment") != std::string::npos ||
                         why.find("cannot map zero-fill pages") != std::string::npos ||
                         why.find("annot allocate memory") != std::string::npos;
    struct statvfs fs_info {};
    return mapping && !(::statvfs(path.c_str(), &fs_info) == 0 && (fs_info.f_flag & ST_NOEXEC));
}

Plugin load() {
    const fs::path path = plugin_path();
    if (const std::string problem = elf_problem(path); !problem.empty())
        throw MediaError(
            fmt::format("cannot load the image and video plugin {}: {} (reinstall it, or set SURFVP_MEDIA_PLUGIN "
                        "to its path)",
                        path.string(), problem));
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const std::string why = dlerror();
        if (mapping_refused(why, path))
            throw OutOfMemory(
                fmt::format("mapping the image and video plugin {} and its libraries ({})", path.string(), why));
        throw MediaError(fmt::format(
            "cannot load the image and video plugin {}: {} (set SURFVP_MEDIA_PLUGIN to its path)", path.string(), why));
    }
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

// A decoded image's cache key: the file by its real path, size and modification time, and the
// flags; empty when the file cannot be stat'ed (then it is decoded, not cached).
std::string image_key(const std::string& path, int flags) {
    std::error_code ec;
    const fs::path real = fs::canonical(path, ec);
    if (ec) return "";
    const auto size = fs::file_size(real, ec);
    if (ec) return "";
    const auto time = fs::last_write_time(real, ec);
    if (ec) return "";
    return fmt::format("image v1 {} size {} mtime {} flags {}", real.string(), size, time.time_since_epoch().count(),
                       flags);
}

// A matrix as "rows cols type\n" and its bytes, and back (nothing for text that is not one).
std::string mat_text(const cv::Mat& m) {
    const cv::Mat c = m.isContinuous() ? m : m.clone();
    return fmt::format("{} {} {}\n", c.rows, c.cols, c.type()) +
           std::string(reinterpret_cast<const char*>(c.data), c.total() * c.elemSize());
}

cv::Mat read_mat_text(const std::string& text) {
    int rows = 0, cols = 0, type = 0;
    const size_t eol = text.find('\n');
    if (eol == std::string::npos || std::sscanf(text.c_str(), "%d %d %d", &rows, &cols, &type) != 3 || rows <= 0 ||
        cols <= 0 || type < 0)
        return {};
    cv::Mat m(rows, cols, type);
    if (text.size() - eol - 1 != m.total() * m.elemSize()) return {};
    std::copy(text.begin() + long(eol) + 1, text.end(), m.data);
    return m;
}

}  // namespace

std::string content_key(const cv::Mat& image) {
    const cv::Mat c = image.isContinuous() ? image : image.clone();
    const std::string_view bytes(reinterpret_cast<const char*>(c.data), c.total() * c.elemSize());
    // FNV-1a over 8-byte words, each product rotated so that a word's high bits reach the low
    // ones of the next (a byte at a time, a 1024x768 frame took ~0.8 ms at every start).
    uint64_t fnv = 1469598103934665603ull;
    size_t i = 0;
    for (uint64_t word; i + 8 <= bytes.size(); i += 8) {
        std::memcpy(&word, bytes.data() + i, 8);
        fnv = (fnv ^ word) * 1099511628211ull;
        fnv = fnv << 29 | fnv >> 35;
    }
    for (; i < bytes.size(); ++i) fnv = (fnv ^ static_cast<unsigned char>(bytes[i])) * 1099511628211ull;
    return fmt::format("{}x{} type {} hash {:016x} {:016x}", c.cols, c.rows, c.type(),
                       std::hash<std::string_view>{}(bytes), fnv);
}

cv::Mat read_image(const std::string& path, int flags) {
    const std::string key = image_key(path, flags);
    if (!key.empty())
        if (auto text = read_cached("image", key))
            if (cv::Mat m = read_mat_text(*text); !m.empty()) return m;
    cv::Mat image;
    plugin().read_image(&path, flags, &image);
    if (!key.empty() && !image.empty()) write_cached("image", key, mat_text(image));
    return image;
}

bool encode_image(const std::string& extension, const cv::Mat& image, std::vector<unsigned char>& bytes) {
    const std::string key = fmt::format("encoded v1 {} {}", extension, content_key(image));
    if (auto text = read_cached("encoded", key); text && !text->empty()) {
        bytes.assign(text->begin(), text->end());
        return true;
    }
    if (!plugin().encode_image(&extension, &image, &bytes)) return false;
    write_cached("encoded", key, std::string(bytes.begin(), bytes.end()));
    return true;
}

Video::Video(const std::string& path) : handle_(plugin().video_open(&path)) {}

Video::~Video() {
    if (handle_) plugin().video_close(handle_);
}

bool Video::grab() { return handle_ && plugin().video_grab(handle_); }

bool Video::read(cv::Mat& frame) { return handle_ && plugin().video_read(handle_, &frame); }

}  // namespace surfvp::media
