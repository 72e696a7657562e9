#pragma once
// Results kept across runs in one folder: what a run would otherwise recompute at every start
// (generated FHG sequences, decoded frames, the threshold calibration's responses). Plain C++.
//
// The folder is $SURFVP_CACHE, else $XDG_CACHE_HOME/surfvp, else ~/.cache/surfvp;
// SURFVP_CACHE=off keeps nothing on disk. An entry is one file named by its kind and a hash of
// its key, holding the key on its first line, then the size and CRC-32 of the data, then the
// data. The folder is shared and nothing in it is trusted: an entry is read only when it is a
// regular file (not a link, a FIFO or a device) of at most kMaxCacheEntry bytes whose key,
// size and checksum all match; anything else (a hash collision, a cut, flipped or foreign
// file) is a miss, and the caller computes the data again and rewrites the entry. So a run's
// results never depend on what the cache held. Files are written whole under a temporary name
// and renamed into place, so concurrent runs share the folder safely. A folder that cannot be
// written only costs the time.
#include <filesystem>
#include <cstdint>
#include <optional>
#include <string>

namespace surfvp {

// The largest entry read back (a decoded 4096x4096 colour frame is 48 MiB).
constexpr std::uintmax_t kMaxCacheEntry = 256u << 20;

// The cache folder, or nothing when SURFVP_CACHE=off (or no home is known).
std::optional<std::filesystem::path> cache_folder();

// The file an entry of `kind` with `key` lives in, inside `folder`.
std::filesystem::path cache_file(const std::filesystem::path& folder, const std::string& kind, const std::string& key);

// The data stored for `key`, or nothing. `key` must be one line (no '\n').
std::optional<std::string> read_cached(const std::string& kind, const std::string& key);

// An entry's whole text: the key, the data's size and checksum, the data.
std::string cache_entry(const std::string& key, const std::string& data);

// Stores `data` for `key`; silently nothing when the cache is off or cannot be written.
void write_cached(const std::string& kind, const std::string& key, const std::string& data);

// The same in a given folder rather than the cache folder.
std::optional<std::string> read_cached_in(const std::filesystem::path& folder, const std::string& kind,
                                          const std::string& key);
void write_cached_in(const std::filesystem::path& folder, const std::string& kind, const std::string& key,
                     const std::string& data);

}  // namespace surfvp
