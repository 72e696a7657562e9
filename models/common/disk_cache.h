#pragma once
// Results kept across runs in one folder: what a run would otherwise recompute at every start
// (generated FHG sequences, decoded frames, the threshold calibration's responses). Plain C++.
//
// The folder is $SURFVP_CACHE, else $XDG_CACHE_HOME/surfvp, else ~/.cache/surfvp;
// SURFVP_CACHE=off keeps nothing on disk. An entry is one file named by its kind and a hash of
// its key, holding the key on its first line and the data after it: a file whose first line is
// not the key (a hash collision, a foreign or cut file) is a miss. Files are written whole
// under a temporary name and renamed into place, so concurrent runs share the folder safely. A
// folder that cannot be written only costs the time.
#include <filesystem>
#include <optional>
#include <string>

namespace surfvp {

// The cache folder, or nothing when SURFVP_CACHE=off (or no home is known).
std::optional<std::filesystem::path> cache_folder();

// The file an entry of `kind` with `key` lives in, inside `folder`.
std::filesystem::path cache_file(const std::filesystem::path& folder, const std::string& kind, const std::string& key);

// The data stored for `key`, or nothing. `key` must be one line (no '\n').
std::optional<std::string> read_cached(const std::string& kind, const std::string& key);

// Stores `data` for `key`; silently nothing when the cache is off or cannot be written.
void write_cached(const std::string& kind, const std::string& key, const std::string& data);

}  // namespace surfvp
