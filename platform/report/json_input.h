#pragma once
// JSON that surfvp reads back rather than writes (a run folder's report.json, a sweep's
// results.json, a database row): untrusted input. Parsing is bounded (nesting, size) and
// refused with the file's name as bad input; lookups are checked, so a missing key or a value
// of another type is a default, never a crash or a library's exception.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace surfvp {

constexpr int kMaxJsonDepth = 64;                   // surfvp's own reports nest 7 deep
constexpr std::uintmax_t kMaxJsonBytes = 1u << 30;  // a report.json of 1,000 frames is ~50 MiB

// A file surfvp reads back, whole; throws ConfigError naming it when it is missing, not a
// regular file, larger than `max_bytes` or unreadable. `what` says what the file was for.
std::string read_input_file(const std::filesystem::path& file, const std::string& what, std::uintmax_t max_bytes);
// Throws ConfigError "WHERE: not valid JSON ..." / "nested deeper than ...".
nlohmann::ordered_json parse_json(const std::string& text, const std::string& where);
// The file as JSON; throws ConfigError naming it when it is missing, not a regular file, too
// large or not JSON. `what` says what the file was for ("the run's report").
nlohmann::ordered_json read_json_file(const std::filesystem::path& file, const std::string& what);

// The value at a JSON pointer ("/power/watts"), or null when any step is missing or not a
// container.
const nlohmann::ordered_json& value_at(const nlohmann::ordered_json& j, std::string_view pointer);
// A number (or the fallback), a string (or the fallback), a flag (or the fallback).
double number_at(const nlohmann::ordered_json& j, std::string_view pointer, double fallback = 0);
std::string text_at(const nlohmann::ordered_json& j, std::string_view pointer, const std::string& fallback = "");
bool flag_at(const nlohmann::ordered_json& j, std::string_view pointer, bool fallback = false);

}  // namespace surfvp
