#pragma once
// One way every layer writes an output file: models (the trace files), the evaluation's keypoint
// files and the platform's reports.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace surfvp {

// The machine refused a write (disk full, permission, a folder that cannot be created): not
// the user's input and not a bug. The message names the file and the system's reason.
struct EnvironmentError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Writes `content` to a temporary name beside `file` and renames it over `file`, so a reader
// never sees a half-written file. Throws EnvironmentError naming the file on failure.
void write_file_atomically(const std::filesystem::path& file, const std::string& content);

}  // namespace surfvp
