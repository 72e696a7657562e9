#include "platform/report/json_input.h"

#include <fmt/format.h>
#include <fstream>

#include "platform/scenario/config.h"

namespace surfvp {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Json parse_json(const std::string& text, const std::string& where) {
    // The parser is not recursive, but everything that walks the value after it is: the depth
    // is refused while parsing, before anything deeper exists.
    const Json::parser_callback_t bounded = [&where](int depth, Json::parse_event_t, Json&) {
        if (depth > kMaxJsonDepth)
            throw ConfigError(fmt::format("{}: nested deeper than {} levels", where, kMaxJsonDepth));
        return true;
    };
    try {
        return Json::parse(text, bounded);
    } catch (const Json::exception& e) {
        throw ConfigError(fmt::format("{}: not valid JSON: {}", where, e.what()));
    }
}

std::string read_input_file(const fs::path& file, const std::string& what, std::uintmax_t max_bytes) {
    std::error_code error;
    const fs::file_status status = fs::status(file, error);
    if (!fs::exists(status)) throw ConfigError(fmt::format("{}: no such file ({})", file.string(), what));
    if (!fs::is_regular_file(status))
        throw ConfigError(fmt::format("{}: is not a regular file ({})", file.string(), what));
    if (fs::file_size(file, error) > max_bytes)
        throw ConfigError(fmt::format("{}: larger than {} MiB, not {}", file.string(), max_bytes >> 20, what));
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ConfigError(fmt::format("{}: cannot be read ({})", file.string(), what));
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

Json read_json_file(const fs::path& file, const std::string& what) {
    return parse_json(read_input_file(file, what, kMaxJsonBytes), file.string());
}

const Json& value_at(const Json& j, std::string_view pointer) {
    static const Json none;
    const Json* at = &j;
    for (size_t from = 1; from <= pointer.size();) {  // pointer starts with '/'
        const size_t to = std::min(pointer.find('/', from), pointer.size());
        const std::string key(pointer.substr(from, to - from));
        if (at->is_object()) {
            const auto it = at->find(key);
            if (it == at->end()) return none;
            at = &*it;
        } else if (at->is_array() && !key.empty() && key.find_first_not_of("0123456789") == std::string::npos &&
                   key.size() < 10 && std::stoul(key) < at->size()) {
            at = &(*at)[std::stoul(key)];
        } else {
            return none;
        }
        from = to + 1;
    }
    return *at;
}

double number_at(const Json& j, std::string_view pointer, double fallback) {
    const Json& v = value_at(j, pointer);
    return v.is_number() ? v.get<double>() : fallback;
}

std::string text_at(const Json& j, std::string_view pointer, const std::string& fallback) {
    const Json& v = value_at(j, pointer);
    return v.is_string() ? v.get<std::string>() : fallback;
}

bool flag_at(const Json& j, std::string_view pointer, bool fallback) {
    const Json& v = value_at(j, pointer);
    return v.is_boolean() ? v.get<bool>() : fallback;
}

}  // namespace surfvp
