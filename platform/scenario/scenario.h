#pragma once
// Scenario files: YAML with one map per section (`plb2: {width: 64 bit}`), plus `name` and
// `description`. Loading checks every key and value against the parameter table and
// applies `--set key=value` overrides after the file, so that a bad scenario is reported
// (file, line, key, what is wrong) before anything runs or is written.
#include <string>
#include <string_view>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "platform/scenario/config.h"

namespace surfvp {

// Throws ConfigError: a file that is not one YAML map, a key given twice (name and
// description too), an unknown key, a wrong unit, a value out of range.
Config load_scenario(const std::string& path, const std::vector<std::string>& overrides);
// One YAML document from a file (a `what`: "scenario", "sweep"); throws ConfigError for a
// file that is missing, not regular, not YAML, or holds several documents.
YAML::Node load_yaml_file(const std::string& path, const std::string& what);
// The folder a file's relative paths start from: its own, or the real file's when `file` is a
// symbolic link (so that a link from another folder means the same files).
std::string folder_of_file(const std::string& file);
// A path parameter's value (a text parameter: surf.source, eval.*) as given in `file`: relative
// to that file's folder (folder_of_file); any other value as it is.
std::string relative_to_file(const std::string& file, const std::string& key, const std::string& value);
// Well-formed UTF-8: what a YAML value must be for config.yaml (or a sweep's results.json) to
// give it back.
bool is_utf8(std::string_view text);
// A scenario's or a sweep's name is its default output folder's (traces/<name>), so it must be
// one folder's name: not empty, '.' or '..', without '/', '\' or control characters. Throws
// ConfigError at `where` (FILE:LINE) otherwise.
void check_folder_name(const std::string& where, const std::string& name);
// `--set KEY=VALUE` overrides, applied in order (a key at most once); throws ConfigError.
void apply_overrides(Config& config, const std::vector<std::string>& overrides);

// A loaded scenario's stated warnings, one line each: every parameter given that has no
// effect in it ("FILE:LINE: surf.threshold = 300 has no effect: ..."). validate and run print
// them; config.yaml notes them beside the value.
std::vector<std::string> scenario_warnings(const Config& config);

// A scenario argument is a file path, or the name of a scenario shipped in scenario_dir().
std::string resolve_scenario(const std::string& argument);
// The tools' optional scenario argument: that scenario, or every parameter at its default when
// it is empty; `--set` overrides applied either way. Throws ConfigError.
Config scenario_or_defaults(const std::string& argument, const std::vector<std::string>& overrides);

// Where shipped scenarios live: $SURFVP_SCENARIOS, else the source tree's scenarios/.
std::string scenario_dir();

struct ShippedScenario {
    std::string name;
    std::string path;
    std::string description;
};
std::vector<ShippedScenario> shipped_scenarios();

}  // namespace surfvp
