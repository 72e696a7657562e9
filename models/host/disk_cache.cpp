#include "models/host/disk_cache.h"

#include <cstdlib>
#include <fcntl.h>
#include <fmt/format.h>
#include <functional>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "models/host/atomic_file.h"

namespace surfvp {
namespace fs = std::filesystem;

std::optional<fs::path> cache_folder() {
    if (const char* dir = std::getenv("SURFVP_CACHE"); dir && *dir) {
        if (std::string(dir) == "off") return std::nullopt;
        return fs::path(dir);
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "surfvp";
    if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "surfvp";
    return std::nullopt;
}

fs::path cache_file(const fs::path& folder, const std::string& kind, const std::string& key) {
    return folder / fmt::format("{}-{:016x}", kind, std::hash<std::string>{}(key));
}

namespace {

// The second line of an entry: what the data after it must be.
std::string seal(const std::string& data) {
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(data.data()), uInt(data.size()));
    return fmt::format("size {} crc32 {:08x}", data.size(), crc);
}

// The whole file, when it is a regular one of plausible size: opened without following a link
// and without blocking on a FIFO, then checked on its descriptor (no race with a rename).
std::optional<std::string> read_entry(const fs::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return std::nullopt;
    struct stat s {};
    std::optional<std::string> text;
    if (::fstat(fd, &s) == 0 && S_ISREG(s.st_mode) && std::uintmax_t(s.st_size) <= kMaxCacheEntry + 4096) {
        text.emplace(size_t(s.st_size), '\0');
        size_t got = 0;
        for (ssize_t n; got < text->size() && (n = ::read(fd, text->data() + got, text->size() - got)) > 0;)
            got += size_t(n);
        if (got != text->size()) text.reset();
    }
    ::close(fd);
    return text;
}

}  // namespace

std::string cache_entry(const std::string& key, const std::string& data) {
    return key + "\n" + seal(data) + "\n" + data;
}

std::optional<std::string> read_cached(const std::string& kind, const std::string& key) {
    const auto folder = cache_folder();
    return folder ? read_cached_in(*folder, kind, key) : std::nullopt;
}

std::optional<std::string> read_cached_in(const fs::path& folder, const std::string& kind, const std::string& key) {
    const auto text = read_entry(cache_file(folder, kind, key));
    if (!text) return std::nullopt;
    const size_t first = text->find('\n'), second = first == std::string::npos ? first : text->find('\n', first + 1);
    if (second == std::string::npos || text->compare(0, first, key) != 0 || first != key.size()) return std::nullopt;
    std::string data = text->substr(second + 1);
    if (text->compare(first + 1, second - first - 1, seal(data)) != 0) return std::nullopt;
    return data;
}

void write_cached(const std::string& kind, const std::string& key, const std::string& data) {
    if (const auto folder = cache_folder()) write_cached_in(*folder, kind, key, data);
}

void write_cached_in(const fs::path& folder, const std::string& kind, const std::string& key, const std::string& data) {
    try {
        std::error_code ignored;
        fs::create_directories(folder, ignored);
        write_file_atomically(cache_file(folder, kind, key), cache_entry(key, data));
    } catch (const EnvironmentError&) {
        // a folder that cannot be written: the result is still right, only not kept
    }
}

}  // namespace surfvp
