#include "platform/scenario/scenario.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <set>
#include <yaml-cpp/yaml.h>

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
                                      node.IsMap() ? "map" : node.IsSequence() ? "list" : "null"));
    return node.Scalar();
}

void apply_section(Config& config, const std::string& path, const std::string& section, const YAML::Node& body,
                   std::set<std::string>& seen) {
    if (!body.IsMap())
        throw ConfigError(fmt::format("{}: '{}' must be a section of parameters (key: value lines indented below it)",
                                      at(path, body), section));
    for (const auto& item : body) {
        const std::string key = section + "." + item.first.Scalar();
        if (!seen.insert(key).second)
            throw ConfigError(fmt::format("{}: {} is set twice", at(path, item.first), key));
        std::string value = scalar(path, key, item.second);
        // Paths in a scenario are relative to the scenario's own folder.
        const ParamSpec* spec = find_parameter(key);
        if (spec && spec->kind == ParamKind::text && !value.empty() && fs::path(value).is_relative())
            value = (fs::path(path).parent_path() / value).lexically_normal().string();
        config.set(key, value, at(path, item.second.IsNull() ? item.first : item.second));
    }
}

YAML::Node parse_file(const std::string& path) {
    std::error_code error;
    if (!fs::exists(path, error)) throw ConfigError(fmt::format("{}: no such scenario file", path));
    if (fs::is_directory(path, error)) throw ConfigError(fmt::format("{}: is a folder, not a scenario file", path));
    try {
        return YAML::LoadFile(path);
    } catch (const YAML::BadFile&) {
        throw ConfigError(fmt::format("{}: cannot be read", path));
    } catch (const YAML::ParserException& e) {
        throw ConfigError(fmt::format("{}:{}: not valid YAML: {}", path, e.mark.line + 1, e.msg));
    }
}

}  // namespace

Config load_scenario(const std::string& path, const std::vector<std::string>& overrides) {
    Config config;
    config.file = path;
    config.name = fs::path(path).stem().string();
    const YAML::Node root = parse_file(path);
    if (!root.IsNull() && !root.IsMap())
        throw ConfigError(fmt::format("{}: a scenario is a map of sections (name:, description:, cpu:, plb1:, ...)",
                                      at(path, root)));
    std::set<std::string> seen;
    for (const auto& item : root) {
        const std::string key = item.first.Scalar();
        if (key == "name") config.name = scalar(path, key, item.second);
        else if (key == "description") config.description = scalar(path, key, item.second);
        else if (key == "faults") config.faults = parse_faults(path, item.second);
        else apply_section(config, path, key, item.second, seen);
    }
    apply_overrides(config, overrides);
    check_faults(config);
    return config;
}

void apply_overrides(Config& config, const std::vector<std::string>& overrides) {
    for (const std::string& o : overrides) {
        const auto eq = o.find('=');
        if (eq == std::string::npos || eq == 0)
            throw ConfigError(fmt::format("--set '{}': expected KEY=VALUE, e.g. plb2.width=64 bit", o));
        if (o.substr(0, eq) == "faults") {  // the whole list, in place of the scenario's
            config.faults = parse_faults_option(o.substr(eq + 1));
            continue;
        }
        config.set(o.substr(0, eq), o.substr(eq + 1), "--set");
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
