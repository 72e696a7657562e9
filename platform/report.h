#pragma once
// report.json and report.md of a run. The JSON is the machine-readable record (stable key
// order, so that the same scenario gives the same bytes but for the wall-clock fields it
// lists); the Markdown is the same content for a person.
#include <nlohmann/json.hpp>
#include <string>

namespace surfvp {

std::string report_markdown(const nlohmann::ordered_json& report);

// A workload's per-frame list (report.json's workload.per_frame) as CSV: a header of its keys,
// a row per frame.
std::string frames_csv(const nlohmann::ordered_json& per_frame);

// Writes `content` to `path` through a temporary file and a rename, so the file is either
// absent or complete. Throws std::runtime_error.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace surfvp
