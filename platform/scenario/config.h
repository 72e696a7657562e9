#pragma once
// The effective configuration of a run: every parameter's value and where it came from
// (the default, a scenario file's line, or --set). Typed getters give the models their
// Params; each value was checked against its ParamSpec when it was set.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/common/fault_plan.h"
#include "models/common/units.h"
#include "platform/scenario/parameters.h"

namespace surfvp {

// Bad input: a scenario, a --set, a parameter combination. The message is complete and
// meant for the user; the CLI exits with code 2.
struct ConfigError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Config : public ParamValues {
public:
    struct Entry {
        const ParamSpec* spec;
        std::string value;
        std::string origin;  // "default", "FILE:LINE" or "--set"
        std::string note;    // why a value given has no effect in this scenario, or ""
        std::string effect;  // what a run used in its place (the calibrated threshold), or ""
    };

    Config();  // every parameter at its default

    // Throws ConfigError naming `where`, the key and the problem.
    void set(const std::string& key, const std::string& value, const std::string& origin);
    // A copy with each (key, value) set from `origin` (a re-simulation's point).
    Config with(const std::vector<std::pair<std::string, std::string>>& sets, const std::string& origin) const;
    // The other way: these keys with their values as written, as points that `with` takes back
    // (a re-simulation at the scenario's own values).
    std::vector<std::pair<std::string, std::string>> sets_of(const std::vector<std::string>& keys) const;

    Frequency frequency(const std::string& key) const override;
    Duration duration(const std::string& key) const override;
    unsigned bits(const std::string& key) const override;
    Bytes bytes(const std::string& key) const override;
    uint64_t cycles(const std::string& key) const override;
    unsigned beats(const std::string& key) const override;
    uint64_t count(const std::string& key) const override;
    double real(const std::string& key) const override;
    uint32_t address(const std::string& key) const override;
    const std::string& choice(const std::string& key) const override;
    const std::string& text(const std::string& key) const override;
    // Any parameter: its value as written, and as a number in its kind's base unit (0 for
    // choices and texts).
    const std::string& value(const std::string& key) const;
    double base_value(const std::string& key) const;

    const std::vector<Entry>& entries() const { return entries_; }

    // Where a parameter's value came from ("FILE:LINE", "--set" or "default"); the same for a
    // message's middle ("FILE:LINE", "--set", "the default"), and for its head ("FILE:LINE:
    // key", "--set key" or "key (default)").
    const std::string& origin(const std::string& key) const;
    std::string source_of(const std::string& key) const;
    std::string where(const std::string& key) const;

    // Records that `key`'s value has no effect, and why: config.yaml says so beside it.
    void note(const std::string& key, const std::string& why);
    void set_effect(const std::string& key, const std::string& what);

    std::string name;           // the scenario's name (its file's stem unless it says)
    std::string description;    // its one-line description
    std::string file;           // the scenario file, as given
    std::vector<Fault> faults;  // to inject (the scenario's faults:, docs/faults.md)

    // The configuration as a scenario YAML that reproduces it, each value commented with
    // its origin.
    std::string to_yaml() const;

private:
    const Entry& entry(const std::string& key, ParamKind kind) const;
    std::vector<Entry> entries_;
};

}  // namespace surfvp
