// The cache folder is shared and untrusted (models/host/disk_cache.h): an entry is used only
// when its key, size and checksum match and it is a regular file of plausible size; anything
// else is a miss, never a block, a crash or other data.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

#include "models/host/disk_cache.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;

fs::path fresh_cache(const char* name) {
    const fs::path dir = fs::temp_directory_path() / fmt::format("surfvp_disk_cache_{}_{}", name, ::getpid());
    fs::remove_all(dir);
    fs::create_directories(dir);
    ::setenv("SURFVP_CACHE", dir.c_str(), 1);
    return dir;
}

std::string slurp(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

void put(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

TEST(DiskCache, AnEntryIsReadBackOnlyWhenKeySizeAndChecksumMatch) {
    const fs::path dir = fresh_cache("checks");
    const std::string key = "threshold v1 graf1", data = std::string("responses\n\0\x01\x02", 13);
    write_cached("ranked", key, data);
    const fs::path entry = cache_file(dir, "ranked", key);
    EXPECT_EQ(slurp(entry), key + "\nsize 13 crc32 " + std::string("117ca78a") + "\n" + data);
    EXPECT_EQ(read_cached("ranked", key), data);
    const std::string whole = slurp(entry);
    put(entry, whole.substr(0, key.size() + 1));  // cut after its key line
    EXPECT_FALSE(read_cached("ranked", key));
    put(entry, whole.substr(0, whole.size() - 1));  // one byte short
    EXPECT_FALSE(read_cached("ranked", key));
    std::string flipped = whole;
    flipped.back() ^= 0x10;  // one bit
    put(entry, flipped);
    EXPECT_FALSE(read_cached("ranked", key));
    put(entry, key + "\n" + data);  // an older surfvp's entry: no checksum
    EXPECT_FALSE(read_cached("ranked", key));
    put(entry, "another key\n" + whole.substr(key.size() + 1));
    EXPECT_FALSE(read_cached("ranked", key));
    write_cached("ranked", key, data);  // rewritten whole
    EXPECT_EQ(read_cached("ranked", key), data);
}

TEST(DiskCache, SpecialFilesLinksAndHugeFilesAreMissesThatNeverBlock) {
    const fs::path dir = fresh_cache("special");
    const fs::path fifo = cache_file(dir, "image", "a fifo");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    EXPECT_FALSE(read_cached("image", "a fifo"));  // would block a plain open
    fs::create_symlink("/dev/zero", cache_file(dir, "image", "a device"));
    EXPECT_FALSE(read_cached("image", "a device"));  // would read without end
    write_cached("image", "linked", "data");
    fs::rename(cache_file(dir, "image", "linked"), dir / "elsewhere");
    fs::create_symlink(dir / "elsewhere", cache_file(dir, "image", "linked"));
    EXPECT_FALSE(read_cached("image", "linked"));  // a link is not followed
    fs::create_directory(cache_file(dir, "image", "a folder"));
    EXPECT_FALSE(read_cached("image", "a folder"));
    const fs::path huge = cache_file(dir, "image", "huge");
    put(huge, "huge\n");
    fs::resize_file(huge, kMaxCacheEntry + (1u << 20));  // sparse
    EXPECT_FALSE(read_cached("image", "huge"));
    write_cached("image", "a folder", "x");  // cannot replace a folder: silently not kept
    EXPECT_FALSE(read_cached("image", "a folder"));
}

}  // namespace
}  // namespace surfvp
