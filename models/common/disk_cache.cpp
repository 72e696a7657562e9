#include "models/common/disk_cache.h"

#include <algorithm>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <functional>

#include "models/common/atomic_file.h"

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

std::optional<std::string> read_cached(const std::string& kind, const std::string& key) {
    const auto folder = cache_folder();
    if (!folder) return std::nullopt;
    std::ifstream in(cache_file(*folder, kind, key), std::ios::binary);
    std::string first;
    if (!in || !std::getline(in, first) || first != key) return std::nullopt;
    // The rest in one read (an image is half a megabyte: byte by byte through a growing string
    // it was a millisecond of every run's start).
    const std::streampos start = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg() - start;
    in.seekg(start);
    std::string data(size_t(std::max<std::streamoff>(size, 0)), '\0');
    if (!in.read(data.data(), std::streamsize(data.size()))) return std::nullopt;
    return data;
}

void write_cached(const std::string& kind, const std::string& key, const std::string& data) {
    const auto folder = cache_folder();
    if (!folder) return;
    try {
        std::error_code ignored;
        fs::create_directories(*folder, ignored);
        write_file_atomically(cache_file(*folder, kind, key), key + "\n" + data);
    } catch (const EnvironmentError&) {
        // a folder that cannot be written: the result is still right, only not kept
    }
}

}  // namespace surfvp
