#pragma once
// One way every layer writes an output file: models (the trace files), the evaluation's keypoint
// files and the platform's reports.
#include <filesystem>
#include <string>

namespace surfvp {

// Writes `content` to a temporary name beside `file` and renames it over `file`, so a reader
// never sees a half-written file. Throws std::runtime_error naming the file on failure.
void write_file_atomically(const std::filesystem::path& file, const std::string& content);

}  // namespace surfvp
