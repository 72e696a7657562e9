#include "platform/scenario/config.h"

#include <algorithm>
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "platform/scenario/faults.h"

namespace surfvp {

Config::Config() {
    for (const ParamSpec& spec : parameter_table()) entries_.push_back({&spec, spec.default_value, "default", "", ""});
}

void Config::set(const std::string& key, const std::string& value, const std::string& origin) {
    for (Entry& e : entries_) {
        if (e.spec->key != key) continue;
        try {
            parse_value(*e.spec, value);
        } catch (const UnitError& error) {
            throw ConfigError(
                fmt::format("{}: {}: {} (expected {})", origin, key, error.what(), describe_kind(*e.spec)));
        }
        e.value = value;
        e.origin = origin;
        return;
    }
    const std::string close = closest_parameter(key);
    throw ConfigError(fmt::format("{}: '{}' is not a parameter{}; `surfvp params` lists them all", origin, key,
                                  close.empty() ? "" : fmt::format(" (did you mean '{}'?)", close)));
}

const Config::Entry& Config::entry(const std::string& key, ParamKind kind) const {
    for (const Entry& e : entries_)
        if (e.spec->key == key) {
            if (e.spec->kind != kind) throw std::logic_error("parameter " + key + " read as the wrong kind");
            return e;
        }
    throw std::logic_error("no parameter " + key);
}

namespace {
ParamKind kind_of(const std::string& key) {
    const ParamSpec* spec = find_parameter(key);
    if (!spec) throw std::logic_error("no parameter " + key);  // callers check keys they were given
    return spec->kind;
}
}  // namespace

const std::string& Config::origin(const std::string& key) const { return entry(key, kind_of(key)).origin; }

std::string Config::source_of(const std::string& key) const {
    const std::string& from = origin(key);
    return from == "default" ? "the default" : from;
}

std::string Config::where(const std::string& key) const {
    const std::string& from = origin(key);
    if (from == "default") return key + " (default)";
    if (from == "--set") return "--set " + key;
    return from + ": " + key;
}

void Config::note(const std::string& key, const std::string& why) {
    for (Entry& e : entries_)
        if (e.spec->key == key) e.note = why;
}

Config Config::with(const std::vector<std::pair<std::string, std::string>>& sets, const std::string& origin) const {
    Config c = *this;
    for (const auto& [key, value] : sets) c.set(key, value, origin);
    return c;
}

std::vector<std::pair<std::string, std::string>> Config::sets_of(const std::vector<std::string>& keys) const {
    std::vector<std::pair<std::string, std::string>> sets;
    for (const std::string& key : keys) sets.emplace_back(key, value(key));
    return sets;
}

void Config::set_effect(const std::string& key, const std::string& what) {
    for (Entry& e : entries_)
        if (e.spec->key == key) e.effect = what;
}

Frequency Config::frequency(const std::string& key) const {
    return parse_frequency(entry(key, ParamKind::frequency).value);
}
Duration Config::duration(const std::string& key) const {
    return parse_duration(entry(key, ParamKind::duration).value);
}
unsigned Config::bits(const std::string& key) const { return parse_bits(entry(key, ParamKind::bits).value); }
Bytes Config::bytes(const std::string& key) const { return parse_bytes(entry(key, ParamKind::bytes).value); }
uint64_t Config::cycles(const std::string& key) const { return parse_cycles(entry(key, ParamKind::cycles).value); }
unsigned Config::beats(const std::string& key) const { return parse_beats(entry(key, ParamKind::beats).value); }
const std::string& Config::value(const std::string& key) const { return entry(key, kind_of(key)).value; }
double Config::base_value(const std::string& key) const {
    const Entry& e = entry(key, kind_of(key));
    return parse_value(*e.spec, e.value);
}
const std::string& Config::choice(const std::string& key) const { return entry(key, ParamKind::choice).value; }
const std::string& Config::text(const std::string& key) const { return entry(key, ParamKind::text).value; }

uint64_t Config::count(const std::string& key) const {
    const Entry& e = entry(key, ParamKind::count);
    return static_cast<uint64_t>(parse_value(*e.spec, e.value));
}
double Config::real(const std::string& key) const {
    const Entry& e = entry(key, ParamKind::real);
    return parse_value(*e.spec, e.value);
}
uint32_t Config::address(const std::string& key) const {
    const Entry& e = entry(key, ParamKind::address);
    return static_cast<uint32_t>(parse_value(*e.spec, e.value));
}

std::string Config::to_yaml() const {
    YAML::Emitter out;
    out << YAML::Comment(
        fmt::format("surfvp effective configuration of '{}': every parameter, with where its value came from", name));
    out << YAML::BeginMap;
    // Double-quoted: escapes keep any text as it was (a lone \r in a plain scalar read back as
    // a line break; found by tests/fuzz scenario).
    out << YAML::Key << "name" << YAML::Value << YAML::DoubleQuoted << name;
    out << YAML::Key << "description" << YAML::Value << YAML::DoubleQuoted << description;
    // One map per section, in the order sections first appear in the table (a section's keys
    // are not all adjacent there: cpu.memory_path follows the CPU's own): a section given twice
    // would not load back.
    std::vector<std::string> sections;
    for (const Entry& e : entries_) {
        const std::string head = e.spec->key.substr(0, e.spec->key.find('.'));
        if (std::find(sections.begin(), sections.end(), head) == sections.end()) sections.push_back(head);
    }
    for (const std::string& section : sections) {
        out << YAML::Key << section << YAML::Value << YAML::BeginMap;
        for (const Entry& e : entries_) {
            const auto dot = e.spec->key.find('.');
            if (e.spec->key.compare(0, dot, section) != 0 || dot != section.size()) continue;
            out << YAML::Key << e.spec->key.substr(dot + 1) << YAML::Value << e.value
                << YAML::Comment((e.origin == "default" ? "default " + e.spec->source : e.origin) +
                                 (e.note.empty() ? "" : "; no effect: " + e.note) +
                                 (e.effect.empty() ? "" : "; " + e.effect));
        }
        out << YAML::EndMap;
    }
    out << YAML::EndMap;
    return std::string(out.c_str()) + "\n" + faults_yaml(faults);
}

}  // namespace surfvp
