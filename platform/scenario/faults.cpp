#include "platform/scenario/faults.h"

#include <algorithm>
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "models/host/yaml_text.h"
#include "platform/scenario/config.h"

namespace surfvp {
namespace {

std::string line_of(const std::string& path, const YAML::Node& node) {
    return path == "--set" ? path : fmt::format("{}:{}", path, node.Mark().line + 1);
}

std::string kinds_list() {
    std::vector<std::string> names;
    for (FaultKind k : fault_kinds()) names.push_back(fault_kind_name(k));
    return fmt::format("{}", fmt::join(names, ", "));
}

uint64_t whole_number(const std::string& where, const std::string& key, const std::string& text) {
    const bool digits = !text.empty() && text.size() <= 18 &&
                        std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!digits) throw ConfigError(fmt::format("{}: faults: {}: '{}' is not a whole number", where, key, text));
    return std::stoull(text);
}

// The keys each kind takes; `block` is implied for the FHG's own faults.
std::vector<std::string> keys_of(FaultKind kind) {
    switch (kind) {
        case FaultKind::bus_error:
            return {"kind", "master", "burst"};
        case FaultKind::fifo_overflow:
        case FaultKind::corrupt_determinant:
            return {"kind", "frame", "block"};
        default:
            return {"kind", "block", "frame"};
    }
}

Fault parse_one(const std::string& path, const YAML::Node& item) {
    const std::string where = line_of(path, item);
    if (!item.IsMap())
        throw ConfigError(
            fmt::format("{}: faults: each fault is a map, e.g. {{kind: lost_interrupt, block: fhg, frame: 3}}", where));
    const YAML::Node kind_node = item["kind"];
    if (!kind_node || !kind_node.IsScalar())
        throw ConfigError(fmt::format("{}: faults: a fault needs a kind: one of {}", where, kinds_list()));
    const auto kind = parse_fault_kind(kind_node.Scalar());
    if (!kind)
        throw ConfigError(
            fmt::format("{}: faults: '{}' is not a fault kind: one of {}", where, kind_node.Scalar(), kinds_list()));
    Fault f;
    f.kind = *kind;
    f.origin = where;
    if (f.kind == FaultKind::fifo_overflow || f.kind == FaultKind::corrupt_determinant) f.block = "fhg";
    const std::vector<std::string> allowed = keys_of(f.kind);
    std::vector<std::string> seen;
    for (const auto& entry : item) {
        const std::string key = entry.first.Scalar();
        const std::string at = line_of(path, entry.first);
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
            throw ConfigError(fmt::format("{}: faults: {} takes {}, not '{}'", at, kind_node.Scalar(),
                                          fmt::join(allowed, ", "), key));
        if (std::find(seen.begin(), seen.end(), key) != seen.end())
            throw ConfigError(fmt::format("{}: faults: {} is given twice", at, key));
        seen.push_back(key);
        if (!entry.second.IsScalar())
            throw ConfigError(fmt::format("{}: faults: {}: expected a single value", at, key));
        const std::string value = entry.second.Scalar();
        if (key == "frame")
            f.frame = whole_number(at, key, value);
        else if (key == "burst")
            f.burst = whole_number(at, key, value);
        else if (key == "block" || key == "master")
            f.block = value;
    }
    const bool bus = f.kind == FaultKind::bus_error;
    for (const char* key :
         bus ? std::vector<const char*>{"master", "burst"} : std::vector<const char*>{"block", "frame"})
        if (std::find(seen.begin(), seen.end(), key) == seen.end() &&
            !(key == std::string("block") && !f.block.empty()))
            throw ConfigError(fmt::format("{}: faults: {} needs {}", where, kind_node.Scalar(),
                                          key == std::string("block") ? "block: iig or fhg" : key));
    if (f.kind == FaultKind::bus_error && f.burst == 0)
        throw ConfigError(fmt::format("{}: faults: burst counts from 1 (the master's first burst)", where));
    return f;
}

}  // namespace

std::vector<Fault> parse_faults(const std::string& path, const YAML::Node& list) {
    if (!list.IsSequence())
        throw ConfigError(fmt::format("{}: faults: a list of faults, each '- {{kind: ..., ...}}' (docs/faults.md)",
                                      line_of(path, list)));
    std::vector<Fault> faults;
    for (const auto& item : list) faults.push_back(parse_one(path, item));
    return faults;
}

std::vector<Fault> parse_faults_option(const std::string& value) {
    YAML::Node node;
    try {
        node = load_yaml(value);
    } catch (const YAML::Exception& e) {
        throw ConfigError(fmt::format("--set faults: not a YAML list: {}", e.msg));
    }
    return parse_faults("--set", node);
}

void check_faults(const Config& c) {
    if (c.faults.empty()) return;
    const Fault& first = c.faults.front();
    if (c.choice("run.workload") != "surf")
        throw ConfigError(
            fmt::format("{}: faults: need run.workload = surf, whose driver (libSSA2) detects and recovers "
                        "from them",
                        first.origin));
    for (const char* key : {"verdict.band", "verdict.break_even", "verdict.software"})
        if (c.choice(key) == "on")
            throw ConfigError(
                fmt::format("{}: faults: the verdict's re-simulations would inject them too: set {} to off "
                            "(and every verdict.* switch)",
                            first.origin, key));
    const uint64_t frames = c.count("surf.frames"), pairs = c.count("soc.accelerators");
    for (const Fault& f : c.faults) {
        const std::string what = f.describe();
        if (f.kind == FaultKind::bus_error) {
            const auto pair = pair_of(f.block);
            const bool named = pair && (pairs == 1 ? f.block.size() == 3 : f.block.size() > 3 && *pair < pairs);
            if (!named)
                throw ConfigError(
                    fmt::format("{}: faults: {}: no PLB2 master '{}' drives this workload: {}", f.origin, what, f.block,
                                pairs == 1 ? "iig or fhg" : fmt::format("iig0..iig{0}, fhg0..fhg{0}", pairs - 1)));
            continue;
        }
        if (f.block != "iig" && f.block != "fhg")
            throw ConfigError(fmt::format("{}: faults: {}: block is iig or fhg, not '{}'", f.origin, what, f.block));
        if ((f.kind == FaultKind::fifo_overflow || f.kind == FaultKind::corrupt_determinant) && f.block != "fhg")
            throw ConfigError(
                fmt::format("{}: faults: {}: only the FHG has a maxima FIFO and determinants", f.origin, what));
        if (f.frame >= frames)
            throw ConfigError(fmt::format("{}: faults: {}: past the last frame (surf.frames = {}: frames 0 to {})",
                                          f.origin, what, frames, frames - 1));
        if ((f.kind == FaultKind::lost_interrupt || f.kind == FaultKind::never_finishes) &&
            c.duration("surf.watchdog").ps == 0)
            throw ConfigError(fmt::format("{}: faults: {}: only the driver's watchdog finds it, and surf.watchdog is 0",
                                          f.origin, what));
        if (f.kind == FaultKind::stuck_interrupt && c.count("surf.spurious_irq_limit") == 0)
            throw ConfigError(
                fmt::format("{}: faults: {}: only surf.spurious_irq_limit finds it, and it is 0", f.origin, what));
    }
}

std::string faults_yaml(const std::vector<Fault>& faults) {
    if (faults.empty()) return "";
    std::string out = "faults:\n";
    for (const Fault& f : faults) {
        if (f.kind == FaultKind::bus_error)
            out += fmt::format("  - {{kind: bus_error, master: {}, burst: {}}}  # {}\n", f.block, f.burst, f.origin);
        else
            out += fmt::format("  - {{kind: {}, block: {}, frame: {}}}  # {}\n", fault_kind_name(f.kind), f.block,
                               f.frame, f.origin);
    }
    return out;
}

}  // namespace surfvp
