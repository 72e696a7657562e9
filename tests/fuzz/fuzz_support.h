#pragma once
// What the fuzz targets share: the input as a file (the readers under test take paths), a
// reader of small fields from the input bytes, and the one way a target reports a bug it
// detected itself (an exception of the wrong type, a broken promise): a message and abort(),
// which libFuzzer records as a crash with the input that caused it.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>

namespace surfvp::fuzz {

[[noreturn]] inline void bug(const std::string& what) {
    std::fprintf(stderr, "surfvp fuzz: BUG: %s\n", what.c_str());
    std::abort();
}

// An exception no target accepts: name it, then abort.
[[noreturn]] inline void unexpected(const std::exception& e) { bug(std::string("unexpected exception: ") + e.what()); }

// A folder of this process's own under the system's temporary folder, removed at exit, so
// that two fuzzers (or two jobs of one) never share a file.
inline const std::filesystem::path& scratch_dir() {
    struct Dir {
        std::filesystem::path path;
        Dir() {
            path = std::filesystem::temp_directory_path() / ("surfvp-fuzz-" + std::to_string(::getpid()));
            std::filesystem::create_directories(path);
        }
        ~Dir() {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const Dir dir;
    return dir.path;
}

// Writes `bytes` to `name` in the scratch folder (replacing it) and returns its path.
inline std::filesystem::path write_scratch(const std::string& name, std::string_view bytes) {
    const std::filesystem::path path = scratch_dir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) bug("cannot write the scratch file " + path.string());
    return path;
}

inline void remove_scratch(const std::string& name) {
    std::error_code ignored;
    std::filesystem::remove(scratch_dir() / name, ignored);
}

// Small fields taken from the front of the input; past its end every field reads 0.
class Bytes {
public:
    Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}

    bool empty() const { return at_ >= size_; }
    uint8_t u8() { return at_ < size_ ? data_[at_++] : 0; }
    uint32_t u32() {  // big-endian, as the chip's registers
        uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v = v << 8 | u8();
        return v;
    }
    std::string_view rest() {
        const std::string_view r(reinterpret_cast<const char*>(data_) + at_, at_ < size_ ? size_ - at_ : 0);
        at_ = size_;
        return r;
    }

private:
    const uint8_t* data_;
    size_t size_;
    size_t at_ = 0;
};

}  // namespace surfvp::fuzz
