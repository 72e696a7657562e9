#include "platform/scenario/scenario.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <map>
#include <string_view>
#include <yaml-cpp/yaml.h>

#include "models/host/yaml_text.h"
#include "platform/scenario/consistency.h"
#include "platform/scenario/faults.h"

namespace surfvp {
namespace fs = std::filesystem;
namespace {

std::string at(const std::string& path, const YAML::Node& node) {
    return fmt::format("{}:{}", path, node.Mark().line + 1);
}

std::string scalar(const std::string& path, const std::string& key, const YAML::Node& node) {
    if (!node.IsScalar())
        throw ConfigError(fmt::format("{}: {}: expected a single value, found a {}", at(path, node), key,
                                      node.IsMap()        ? "map"
                                      : node.IsSequence() ? "list"
                                                          : "null"));
    if (!is_utf8(node.Scalar())) throw ConfigError(fmt::format("{}: {}: not UTF-8 text", at(path, node), key));
    return node.Scalar();
}

// A key is a plain word: a list or map as a key (`? [a, b]`) names nothing.
std::string key_of(const std::string& path, const YAML::Node& key) {
    if (!key.IsScalar() || key.Scalar().empty())
        throw ConfigError(fmt::format("{}: a key must be a plain name, not a {}", at(path, key),
                                      key.IsMap()        ? "map"
                                      : key.IsSequence() ? "list"
                                                         : "empty value"));
    return key.Scalar();
}

void apply_section(Config& config, const std::string& path, const std::string& section, const YAML::Node& body,
                   std::map<std::string, std::string>& seen) {
    if (!body.IsMap())
        throw ConfigError(fmt::format("{}: '{}' must be a section of parameters (key: value lines indented below it)",
                                      at(path, body), section));
    for (const auto& item : body) {
        const std::string key = section + "." + key_of(path, item.first);
        // yaml-cpp keeps both of two equal keys: the second would silently win.
        const auto [first, fresh] = seen.emplace(key, at(path, item.first));
        if (!fresh)
            throw ConfigError(
                fmt::format("{}: {} is set twice (first at {})", at(path, item.first), key, first->second));
        const std::string value = relative_to_file(path, key, scalar(path, key, item.second));
        config.set(key, value, at(path, item.second.IsNull() ? item.first : item.second));
    }
}

}  // namespace

// Well-formed UTF-8 (no overlong forms, surrogates or code points above U+10FFFF). YAML is
// Unicode text, and config.yaml could not give back a value that is not: its writer replaces
// each stray byte with U+FFFD, so such a value is refused here, where it can be named.
bool is_utf8(std::string_view text) {
    for (size_t i = 0; i < text.size();) {
        const auto byte = [&](size_t k) { return k < text.size() ? uint8_t(text[k]) : uint8_t(0); };
        const uint8_t lead = byte(i);
        const size_t length = lead < 0x80           ? 1
                              : (lead >> 5) == 0x6  ? 2
                              : (lead >> 4) == 0xE  ? 3
                              : (lead >> 3) == 0x1E ? 4
                                                    : 0;
        if (length == 0) return false;
        uint32_t code = length == 1 ? lead : lead & (0x7F >> length);
        for (size_t k = 1; k < length; ++k) {
            if ((byte(i + k) & 0xC0) != 0x80) return false;
            code = code << 6 | (byte(i + k) & 0x3F);
        }
        const uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
        if (code < least[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return false;
        i += length;
    }
    return true;
}

// The default output folder is traces/<name>: a name is one folder's name, so that no
// scenario (nor sweep) writes outside traces/.
void check_folder_name(const std::string& where, const std::string& name) {
    const bool plain =
        !name.empty() && name != "." && name != ".." &&
        std::none_of(name.begin(), name.end(), [](unsigned char c) { return c == '/' || c == '\\' || c < ' '; });
    if (!plain)
        throw ConfigError(
            fmt::format("{}: name '{}' cannot name the output folder traces/<name>: it must not be empty, "
                        "'.' or '..', nor hold '/', '\\' or control characters",
                        where, name));
}

// A file reached through a symbolic link is read where it lies: its paths are relative to
// the real file's folder, so every spelling of it means the same files.
std::string folder_of_file(const std::string& file) {
    std::error_code error;
    if (!fs::is_symlink(file, error)) return fs::path(file).parent_path().string();
    const fs::path real = fs::weakly_canonical(file, error);
    return (error ? fs::path(file) : real).parent_path().string();
}

std::string relative_to_file(const std::string& file, const std::string& key, const std::string& value) {
    const ParamSpec* spec = find_parameter(key);
    if (spec && spec->kind == ParamKind::text && !value.empty() && fs::path(value).is_relative())
        return (fs::path(folder_of_file(file)) / value).lexically_normal().string();
    return value;
}

YAML::Node load_yaml_file(const std::string& path, const std::string& what) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (!fs::exists(status)) throw ConfigError(fmt::format("{}: no such {} file", path, what));
    if (fs::is_directory(status)) throw ConfigError(fmt::format("{}: is a folder, not a {} file", path, what));
    // A FIFO or a device would be read until it ends, which may be never.
    if (!fs::is_regular_file(status)) throw ConfigError(fmt::format("{}: is not a regular file", path));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ConfigError(fmt::format("{}: cannot be read", path));
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<YAML::Node> documents;
    try {
        documents = load_all_yaml(text);
    } catch (const YAML::ParserException& e) {
        throw ConfigError(fmt::format("{}:{}: not valid YAML: {}", path, e.mark.line + 1, e.msg));
    }
    // Two files pasted into one: which one was meant is not ours to guess.
    if (documents.size() > 1)
        throw ConfigError(fmt::format("{}: holds {} YAML documents (the second starts near line {}); a {} is one", path,
                                      documents.size(), documents[1].Mark().line + 1, what));
    return documents.empty() ? YAML::Node() : documents[0];
}

Config load_scenario(const std::string& path, const std::vector<std::string>& overrides) {
    Config config;
    config.file = path;
    config.name = fs::path(path).stem().string();
    const YAML::Node root = load_yaml_file(path, "scenario");
    if (!root.IsNull() && !root.IsMap())
        throw ConfigError(
            fmt::format("{}: a scenario is a map of sections (name:, description:, cpu:, plb1:, ...)", at(path, root)));
    std::map<std::string, std::string> seen;  // every key given, and where
    for (const auto& item : root) {
        const std::string key = key_of(path, item.first);
        const bool whole_section = key != "name" && key != "description";
        const auto [first, fresh] = seen.emplace(whole_section ? key + ":" : key, at(path, item.first));
        if (!fresh)
            throw ConfigError(fmt::format("{}: {} appears twice (first at {})", at(path, item.first),
                                          whole_section ? "section '" + key + "'" : "'" + key + "'", first->second));
        if (key == "name") {
            config.name = scalar(path, key, item.second);
            check_folder_name(at(path, item.second), config.name);
        } else if (key == "description") {
            config.description = scalar(path, key, item.second);
        } else if (key == "faults") {
            config.faults = parse_faults(path, item.second);
        } else {
            apply_section(config, path, key, item.second, seen);
        }
    }
    apply_overrides(config, overrides);
    check_faults(config);
    for (const Ineffective& i : ineffective_parameters(config)) config.note(i.key, i.reason);
    return config;
}

std::vector<std::string> scenario_warnings(const Config& config) {
    std::vector<std::string> out;
    for (const Config::Entry& e : config.entries())
        if (!e.note.empty())
            out.push_back(fmt::format("{} = {} has no effect: {}", config.where(e.spec->key), e.value, e.note));
    return out;
}

void apply_overrides(Config& config, const std::vector<std::string>& overrides) {
    std::map<std::string, std::string> given;
    for (const std::string& o : overrides) {
        const auto eq = o.find('=');
        if (eq == std::string::npos || eq == 0)
            throw ConfigError(fmt::format("--set '{}': expected KEY=VALUE, e.g. plb2.width=64 bit", o));
        if (!is_utf8(o)) throw ConfigError(fmt::format("--set '{}': not UTF-8 text", o));
        const std::string key = o.substr(0, eq), value = o.substr(eq + 1);
        // The first of two would silently not count.
        if (const auto it = given.find(key); it != given.end())
            throw ConfigError(fmt::format("--set {}: given twice ('{}', then '{}')", key, it->second, value));
        given.emplace(key, value);
        if (key == "faults")
            config.faults = parse_faults_option(value);  // the whole list, in place of the scenario's
        else
            config.set(key, value, "--set");
    }
}

std::string scenario_dir() {
    if (const char* dir = std::getenv("SURFVP_SCENARIOS")) return dir;
    return SURFVP_SCENARIO_DIR;
}

std::string resolve_scenario(const std::string& argument) {
    std::error_code error;
    // A file, or anything that looks like a path, is taken as it is; a bare name (even one a
    // folder in the current directory has, such as an earlier run's output) is a shipped one.
    if (fs::is_regular_file(argument, error) || argument.find('/') != std::string::npos ||
        fs::path(argument).extension() == ".yaml")
        return argument;
    const fs::path shipped = fs::path(scenario_dir()) / (argument + ".yaml");
    return fs::exists(shipped, error) ? shipped.string() : argument;
}

Config scenario_or_defaults(const std::string& argument, const std::vector<std::string>& overrides) {
    if (!argument.empty()) return load_scenario(resolve_scenario(argument), overrides);
    Config config;
    apply_overrides(config, overrides);
    return config;
}

std::vector<ShippedScenario> shipped_scenarios() {
    std::vector<ShippedScenario> out;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(scenario_dir(), error)) {
        if (entry.path().extension() != ".yaml") continue;
        ShippedScenario s{entry.path().stem().string(), entry.path().string(), ""};
        try {
            const Config c = load_scenario(s.path, {});
            s.name = c.name;
            s.description = c.description;
        } catch (const ConfigError& e) {
            s.description = fmt::format("(does not load: {})", e.what());
        }
        out.push_back(s);
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    return out;
}

}  // namespace surfvp
