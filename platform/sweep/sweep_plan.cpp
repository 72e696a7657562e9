#include "platform/sweep/sweep_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "platform/scenario/scenario.h"

namespace surfvp {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
namespace {

std::string at(const std::string& path, const YAML::Node& node) {
    return fmt::format("{}:{}", path, node.Mark().line + 1);
}

std::string scalar(const std::string& path, const YAML::Node& node, const std::string& what) {
    if (!node.IsScalar())
        throw ConfigError(fmt::format("{}: {}: expected a single value, found a {}", at(path, node), what,
                                      node.IsMap()        ? "map"
                                      : node.IsSequence() ? "list"
                                                          : "null"));
    // The name, values and description go into results.json, which holds only UTF-8 text.
    if (!is_utf8(node.Scalar())) throw ConfigError(fmt::format("{}: {}: not UTF-8 text", at(path, node), what));
    return node.Scalar();
}

// A value as the sweep keeps it: a path parameter's (surf.source, eval.*) is its file's one
// absolute spelling, symbolic links and '..' resolved, so that a sweep run from another folder
// or through another spelling of its file has the same points; any other value as written.
std::string resolved(const std::string& file, const std::string& key, const std::string& value) {
    const std::string v = relative_to_file(file, key, value);
    const ParamSpec* spec = find_parameter(key);
    if (!spec || spec->kind != ParamKind::text || v.empty()) return v;
    std::error_code ec;
    const fs::path absolute = fs::absolute(v, ec);
    if (ec) return fs::path(v).lexically_normal().string();
    const fs::path canonical = fs::weakly_canonical(absolute, ec);
    return (ec ? absolute.lexically_normal() : canonical).string();
}

std::pair<double, std::string> quantity(const std::string& text, const std::string& where) {
    const auto q = split_quantity(text);
    if (!q && split_quantity(text, true))
        throw ConfigError(fmt::format("{}: '{}' is out of range (not a finite number)", where, text));
    if (!q) throw ConfigError(fmt::format("{}: '{}' is not a number with an optional unit", where, text));
    return *q;
}

SweepAxis parse_axis(const std::string& path, const YAML::Node& key, const YAML::Node& body) {
    SweepAxis axis{scalar(path, key, "axis"), {}, at(path, key)};
    if (!find_parameter(axis.key))
        throw ConfigError(
            fmt::format("{}: axis {}: no such parameter (surfvp params lists them)", axis.origin, axis.key));
    if (body.IsSequence()) {
        for (const auto& v : body) axis.values.push_back(resolved(path, axis.key, scalar(path, v, axis.key)));
    } else if (body.IsMap()) {
        std::map<std::string, std::string> range;
        for (const auto& item : body) {
            const std::string k = scalar(path, item.first, axis.key);
            if (k != "from" && k != "to" && k != "step")
                throw ConfigError(
                    fmt::format("{}: axis {}: '{}' is not from, to or step", at(path, item.first), axis.key, k));
            range[k] = scalar(path, item.second, axis.key + "." + k);
        }
        for (const char* k : {"from", "to", "step"})
            if (!range.count(k))
                throw ConfigError(fmt::format("{}: axis {}: a range needs from, to and step ('{}' is missing)",
                                              at(path, body), axis.key, k));
        axis.values = expand_range(range["from"], range["to"], range["step"], at(path, body) + ": axis " + axis.key);
    } else {
        axis.values.push_back(resolved(path, axis.key, scalar(path, body, axis.key)));
    }
    if (axis.values.empty()) throw ConfigError(fmt::format("{}: axis {} has no values", axis.origin, axis.key));
    return axis;
}

// Every value on its parameter, at its line, before anything runs (one copy of the base per
// axis: a value set replaces the one before).
void check_values(const SweepPlan& plan, const Config& base) {
    for (const SweepAxis& axis : plan.axes) {
        Config c = base;
        for (const std::string& v : axis.values) c.set(axis.key, v, axis.origin);
    }
}

// How many points the axes make, known before any is made: zipped, the axes' common length;
// crossed, the product of their lengths, multiplied with a check at each step, so that five
// axes of a thousand values are refused in a moment instead of filling the memory (or
// wrapping around to a small number).
size_t point_count(const std::vector<SweepAxis>& axes, bool zip, const std::string& where) {
    if (axes.empty()) return 1;
    size_t n = zip ? axes[0].values.size() : 1;
    bool over = false;
    for (const SweepAxis& a : axes) {
        if (zip && a.values.size() != n)
            throw ConfigError(fmt::format("{}: combine: zip needs axes of one length: {} has {} values, {} has {}",
                                          where, axes[0].key, n, a.key, a.values.size()));
        if (!zip) over = over || __builtin_mul_overflow(n, a.values.size(), &n);
    }
    if (!over && n <= kMaxSweepPoints) return n;
    long double product = 1;
    std::vector<std::string> sizes;
    for (const SweepAxis& a : axes) {
        product *= zip ? 1 : (long double)a.values.size();
        sizes.push_back(fmt::format("{} ({} values)", a.key, a.values.size()));
    }
    if (zip) product = (long double)n;
    throw ConfigError(fmt::format(
        "{}: combine: the axes make {} points, more than the {} a sweep may have: {}", where,
        product < 1e18L ? fmt::format("{}", (unsigned long long)product) : fmt::format("{:.3g}", double(product)),
        kMaxSweepPoints, fmt::join(sizes, fmt::format(" {} ", zip ? "with" : "x"))));
}

std::vector<SweepPoint> combine(const std::vector<SweepAxis>& axes, bool zip, size_t n) {
    std::vector<SweepPoint> points;
    if (axes.empty()) return {SweepPoint{0, {}, point_id({})}};
    points.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        SweepPoint p{i, {}, ""};
        size_t rest = i;
        // Cartesian: the last axis varies fastest.
        std::vector<size_t> pick(axes.size());
        for (size_t a = axes.size(); a-- > 0;) {
            pick[a] = zip ? i : rest % axes[a].values.size();
            if (!zip) rest /= axes[a].values.size();
        }
        for (size_t a = 0; a < axes.size(); ++a) p.values.emplace_back(axes[a].key, axes[a].values[pick[a]]);
        p.id = point_id(p.values);
        points.push_back(std::move(p));
    }
    return points;
}

// The sweep's content, not the spelling of its files: the base scenario's text, the sets (by
// key: their order in the file changes nothing), the axes in order, and how they combine.
Json identity_of(const SweepPlan& plan) {
    std::ifstream in(plan.scenario, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    std::map<std::string, std::string> sets;
    for (const std::string& s : plan.sets) sets[s.substr(0, s.find('='))] = s.substr(s.find('=') + 1);
    Json axes = Json::array();
    for (const SweepAxis& a : plan.axes) axes.push_back({{"key", a.key}, {"values", a.values}});
    return {{"surfvp", SURFVP_VERSION},
            {"scenario", text.str()},
            {"set", sets},
            {"axes", axes},
            {"combine", plan.zip ? "zip" : "cartesian"}};
}

// A list of values for a message: the first few, then how many more.
std::string some(const std::vector<std::string>& values) {
    constexpr size_t shown = 6;
    const std::vector<std::string> head(values.begin(), values.begin() + long(std::min(values.size(), shown)));
    return fmt::format("{}{}", fmt::join(head, ", "),
                       values.size() > shown ? fmt::format(", ... ({} in all)", values.size()) : std::string());
}

std::vector<std::string> set_changes(const Json& before, const Json& now) {
    std::vector<std::string> out;
    for (const auto& [key, value] : now.items())
        if (!before.contains(key))
            out.push_back(fmt::format("{} added", key));
        else if (before[key] != value)
            out.push_back(fmt::format("{}: {}, now {}", key, before[key].get<std::string>(), value.get<std::string>()));
    for (const auto& [key, value] : before.items())
        if (!now.contains(key)) out.push_back(fmt::format("{} removed", key));
    return out;
}

std::vector<std::string> axis_changes(const Json& before, const Json& now) {
    std::vector<std::string> keys_before, keys_now, out;
    std::map<std::string, std::vector<std::string>> values_before;
    for (const Json& a : before) {
        keys_before.push_back(a.at("key").get<std::string>());
        values_before[keys_before.back()] = a.at("values").get<std::vector<std::string>>();
    }
    std::vector<std::string> added, removed, common;
    for (const Json& a : now) {
        const std::string key = a.at("key").get<std::string>();
        keys_now.push_back(key);
        const auto it = values_before.find(key);
        if (it == values_before.end()) {
            added.push_back(key);
            continue;
        }
        common.push_back(key);
        const auto values = a.at("values").get<std::vector<std::string>>();
        if (values != it->second)
            out.push_back(fmt::format("axis {}: values changed ({}; now {})", key, some(it->second), some(values)));
    }
    for (const std::string& k : keys_before)
        if (std::find(keys_now.begin(), keys_now.end(), k) == keys_now.end()) removed.push_back(k);
    if (!added.empty()) out.push_back(fmt::format("axes added: {}", fmt::join(added, ", ")));
    if (!removed.empty()) out.push_back(fmt::format("axes removed: {}", fmt::join(removed, ", ")));
    std::vector<std::string> common_before;
    for (const std::string& k : keys_before)
        if (std::find(common.begin(), common.end(), k) != common.end()) common_before.push_back(k);
    if (common_before != common)  // the order decides the points' indices
        out.push_back(
            fmt::format("axes reordered ({}; now {})", fmt::join(common_before, ", "), fmt::join(common, ", ")));
    return out;
}

}  // namespace

std::vector<std::string> sweep_changes(const std::string& before_text, const std::string& now_text) {
    if (before_text == now_text) return {};
    // Either may be read from a database: one of an earlier surfvp kept its sweep as other
    // text, and a damaged one may hold anything.
    const Json before = Json::parse(before_text, nullptr, false), now = Json::parse(now_text, nullptr, false);
    const char* unknown = "one of them was made by an earlier surfvp, or its record of the sweep is damaged";
    if (!before.is_object() || !now.is_object()) return {unknown};
    std::vector<std::string> out;
    try {
        if (before.at("surfvp") != now.at("surfvp"))
            out.push_back(fmt::format("made by surfvp {} (this is {})", before.at("surfvp").get<std::string>(),
                                      now.at("surfvp").get<std::string>()));
        if (before.at("scenario") != now.at("scenario")) out.push_back("base scenario changed");
        if (const auto sets = set_changes(before.at("set"), now.at("set")); !sets.empty())
            out.push_back(fmt::format("set changed ({})", fmt::join(sets, "; ")));
        for (const std::string& a : axis_changes(before.at("axes"), now.at("axes"))) out.push_back(a);
        if (before.at("combine") != now.at("combine"))
            out.push_back(fmt::format("combine changed ({}, now {})", before.at("combine").get<std::string>(),
                                      now.at("combine").get<std::string>()));
    } catch (const Json::exception&) {
        return {unknown};
    }
    if (out.empty()) out.push_back("their records of the sweep differ");  // in a way the phrases above do not name
    return out;
}

std::string point_id(const std::vector<std::pair<std::string, std::string>>& values) {
    if (values.empty()) return "(base)";
    std::string id;
    for (const auto& [key, value] : values) id += fmt::format("{}{}={}", id.empty() ? "" : ", ", key, value);
    return id;
}

std::optional<std::pair<double, std::string>> split_quantity(const std::string& text, bool any_magnitude) {
    static const std::regex form(R"(\s*([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*([A-Za-z]*)\s*)");
    std::smatch m;
    if (!std::regex_match(text, m, form)) return std::nullopt;
    // strtod, not stod: "1e400" is a number too large for a double, not an exception.
    const double value = std::strtod(m[1].str().c_str(), nullptr);
    if (!std::isfinite(value) && !any_magnitude) return std::nullopt;
    return std::make_pair(value, m[2].str());
}

std::vector<std::string> expand_range(const std::string& from, const std::string& to, const std::string& step,
                                      const std::string& where, size_t limit) {
    const auto [a, unit] = quantity(from, where);
    const auto [b, to_unit] = quantity(to, where);
    const auto [d, step_unit] = quantity(step, where);
    if (to_unit != unit || (!step_unit.empty() && step_unit != unit))
        throw ConfigError(
            fmt::format("{}: from, to and step must share one unit ('{}', '{}', '{}')", where, from, to, step));
    if (!(d > 0)) throw ConfigError(fmt::format("{}: step {} must be above zero", where, step));
    if (b < a) throw ConfigError(fmt::format("{}: to ({}) is below from ({})", where, to, from));
    // A step that lands on `to` within rounding includes it.
    const double steps = std::floor((b - a) / d * (1 + 1e-12) + 1e-9);
    if (steps + 1 > double(limit))
        throw ConfigError(fmt::format("{}: {} values, more than {} in one axis", where, steps + 1, limit));
    std::vector<std::string> out;
    for (size_t i = 0; i <= size_t(steps); ++i) {
        const double v = a + double(i) * d;
        out.push_back(unit.empty() ? fmt::format("{:.12g}", v) : fmt::format("{:.12g} {}", v, unit));
    }
    return out;
}

Config SweepPlan::config(const SweepPoint& point) const {
    std::vector<std::string> all = sets;
    for (const auto& [key, value] : point.values) all.push_back(key + "=" + value);
    return load_scenario(scenario, all);
}

SweepPlan load_sweep(const std::string& path) {
    const YAML::Node root = load_yaml_file(path, "sweep");
    if (!root.IsMap())
        throw ConfigError(fmt::format("{}: a sweep is a map (name:, scenario:, set:, axes:, combine:)", path));
    SweepPlan plan;
    plan.file = path;
    plan.name = fs::path(path).stem().string();
    std::map<std::string, std::string> seen;
    YAML::Node axes;
    std::string combine_where = path;
    for (const auto& item : root) {
        const std::string key = scalar(path, item.first, "key");
        if (const auto [first, fresh] = seen.emplace(key, at(path, item.first)); !fresh)
            throw ConfigError(
                fmt::format("{}: '{}' appears twice (first at {})", at(path, item.first), key, first->second));
        if (key == "name") {
            // The default sweep folder is traces/<name>, as a scenario's output folder.
            plan.name = scalar(path, item.second, key);
            check_folder_name(at(path, item.second), plan.name);
        } else if (key == "description")
            plan.description = scalar(path, item.second, key);
        else if (key == "scenario") {
            // A path is relative to the sweep file's folder; a bare name is a shipped scenario.
            const std::string s = scalar(path, item.second, key);
            const bool a_path = s.find('/') != std::string::npos || fs::path(s).extension() == ".yaml";
            plan.scenario = a_path && fs::path(s).is_relative()
                                ? (fs::path(folder_of_file(path)) / s).lexically_normal().string()
                                : resolve_scenario(s);
        } else if (key == "set") {
            if (!item.second.IsMap())
                throw ConfigError(fmt::format("{}: set: a map of KEY: VALUE", at(path, item.second)));
            for (const auto& s : item.second) {
                const std::string k = scalar(path, s.first, "set");
                plan.sets.push_back(k + "=" + resolved(path, k, scalar(path, s.second, k)));
            }
        } else if (key == "axes") {
            if (!item.second.IsMap())
                throw ConfigError(fmt::format("{}: axes: a map of KEY: values", at(path, item.second)));
            axes = item.second;
        } else if (key == "combine") {
            const std::string c = scalar(path, item.second, key);
            if (c != "cartesian" && c != "zip")
                throw ConfigError(fmt::format("{}: combine: '{}' is not cartesian or zip", at(path, item.second), c));
            plan.zip = c == "zip";
            combine_where = at(path, item.second);
        } else {
            throw ConfigError(
                fmt::format("{}: '{}' is not a sweep key (name, description, scenario, set, axes, combine)",
                            at(path, item.first), key));
        }
    }
    if (!seen.count("name")) check_folder_name(path, plan.name);  // the file's stem: "..yaml" gives "."
    if (plan.scenario.empty())
        throw ConfigError(fmt::format("{}: a sweep names its base scenario (scenario: NAME_OR_PATH)", path));
    std::map<std::string, std::string> axis_at;
    for (const auto& item : axes) {
        SweepAxis axis = parse_axis(path, item.first, item.second);
        if (const auto [first, fresh] = axis_at.emplace(axis.key, axis.origin); !fresh)
            throw ConfigError(
                fmt::format("{}: axis {} is given twice (first at {})", axis.origin, axis.key, first->second));
        plan.axes.push_back(std::move(axis));
    }
    const size_t count = point_count(plan.axes, plan.zip,
                                     seen.count("combine") ? combine_where
                                     : seen.count("axes")  ? seen["axes"]
                                                           : path);
    const Config base = load_scenario(plan.scenario, plan.sets);
    for (const SweepAxis& axis : plan.axes)
        for (const std::string& s : plan.sets)
            if (s.rfind(axis.key + "=", 0) == 0)
                throw ConfigError(fmt::format("{}: axis {} is also in set:", axis.origin, axis.key));
    check_values(plan, base);
    plan.points = combine(plan.axes, plan.zip, count);
    plan.identity = identity_of(plan);
    plan.fingerprint = plan.identity.dump();
    return plan;
}

std::vector<SweepPoint> combine_axes(const std::vector<SweepAxis>& axes, bool zip, const std::string& where) {
    return combine(axes, zip, point_count(axes, zip, where));
}

}  // namespace surfvp
