#include "platform/compare/compare.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <set>
#include <sstream>

#include "models/host/atomic_file.h"
#include "platform/compare/run_figures.h"
#include "platform/run/run.h"
#include "platform/report/figure_format.h"
#include "platform/report/json_input.h"
#include "platform/report/run_summary.h"
#include "platform/scenario/parameters.h"
#include "platform/scenario/scenario.h"
#include "platform/sweep/sweep_results.h"

namespace surfvp {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// A run folder's or sweep's JSON: untrusted (someone else's folder, another version).
Json read_object(const fs::path& file, const std::string& side) {
    if (!fs::exists(file))
        throw ConfigError(fmt::format("{}: no {} (not a run folder?)", side, file.filename().string()));
    Json j = read_json_file(file, "a side of compare");
    if (!j.is_object()) throw ConfigError(fmt::format("{}: {} is not a JSON object", side, file.string()));
    return j;
}

// config.yaml as section.key -> value, read as plain YAML (a run of another version may have
// keys this one does not know).
Json read_parameters(const fs::path& file) {
    Json out = Json::object();
    if (!fs::exists(file)) return out;
    const YAML::Node root = load_yaml_file(file.string(), "configuration");
    if (!root.IsMap()) throw ConfigError(fmt::format("{}: a configuration is a map of sections", file.string()));
    for (const auto& section : root)
        if (section.first.IsScalar() && section.second.IsMap())
            for (const auto& item : section.second)
                if (item.first.IsScalar() && item.second.IsScalar())
                    out[section.first.Scalar() + "." + item.first.Scalar()] = item.second.Scalar();
    return out;
}

Json object_or_empty(const Json& j) { return j.is_object() ? j : Json::object(); }

// The unit of a report.json figure: the statistics legend's, else what its name says
// ("phases_ms.determinants": ms, "mci.utilisation": a share).
std::string unit_of_path(const Json& legend, const std::string& path) {
    if (legend.contains(path)) {
        const Json& unit = value_at(legend[path], "/unit");
        if (unit.is_string() && !unit.get<std::string>().empty()) return unit.get<std::string>();
    }
    auto ends = [&](const std::string& tail) {
        return path.size() >= tail.size() && path.compare(path.size() - tail.size(), tail.size(), tail) == 0;
    };
    if (ends("_ms") || path.find("_ms.") != std::string::npos) return "ms";
    if (ends("_s")) return "s";
    if (ends("_us")) return "us";
    if (ends("cycles") || ends("cycles_per_keypoint")) return "cycles";
    if (ends("_hz")) return "Hz";
    if (ends("fps")) return "frames/s";
    if (ends("bytes")) return "B";
    if (ends("share") || ends("utilisation")) return "share";
    return "";
}

// What a parameter's 0 stands for ("the sequence's" for fhg.cycles_per_block), from its
// description's "(0: ...)" or "; 0: ..."; "" when 0 is a value like any other.
std::string sentinel_meaning(const std::string& key) {
    const ParamSpec* spec = find_parameter(key);
    if (!spec) return "";
    const std::string& d = spec->description;
    for (const char* mark : {"(0: ", "; 0: "}) {
        const size_t at = d.find(mark);
        if (at == std::string::npos) continue;
        const size_t from = at + std::string(mark).size(), end = d.find_first_of(");", from);
        return d.substr(from, end == std::string::npos ? std::string::npos : end - from);
    }
    return "";
}

// What a run did where its parameter said "0: ...": the figure its report gives instead.
Json effective_values(const Json& report) {
    Json e = Json::object();
    if (const Json& c = value_at(report, "/fhg/cycles_per_block"); c.is_number())
        e["fhg.cycles_per_block"] = fmt::format("{} cycles", c.get<double>());
    if (const Json& w = value_at(report, "/image/width"); w.is_number()) e["surf.width"] = w.dump();
    if (const Json& h = value_at(report, "/image/height"); h.is_number()) e["surf.height"] = h.dump();
    return e;
}

// A parameter's value as a side has it; a 0 that stands for something says what, and what the
// run made of it ("0 cycles (the sequence's: 53 cycles)").
Json shown_parameter(const std::string& key, const Json& value, const Json& effective) {
    if (!value.is_string()) return value;
    const std::string meaning = sentinel_meaning(key);
    const ParamSpec* spec = find_parameter(key);
    if (meaning.empty() || !spec) return value;
    try {
        if (parse_value(*spec, value.get<std::string>()) != 0) return value;
    } catch (const std::exception&) {
        return value;
    }
    const Json& actual = effective.contains(key) ? effective[key] : Json();
    return fmt::format("{} ({}{})", value.get<std::string>(), meaning,
                       actual.is_string() ? ": " + actual.get<std::string>() : "");
}

// SWEEP_DIR@POINT: the point's row of the sweep's results.json.
Json load_point(const std::string& side, const fs::path& dir, const std::string& number) {
    if (number.size() > 9) throw ConfigError(fmt::format("{}: no sweep has point {}", side, number));
    const size_t point = std::stoul(number);
    const fs::path file = dir / "results.json";
    const Json results = read_object(file, side);
    const Json& points = value_at(results, "/points");
    if (!points.is_array()) throw ConfigError(fmt::format("{}: {} has no list of points", side, file.string()));
    for (const auto& p : points)
        if (number_at(p, "/point", -1) == double(point))
            return {{"name", side},
                    {"kind", "sweep point"},
                    {"parameters", object_or_empty(value_at(p, "/params"))},
                    {"effective", Json::object()},
                    {"main", object_or_empty(value_at(p, "/figures"))},
                    {"all", Json::object()},
                    {"legend", Json::object()}};
    throw ConfigError(fmt::format("{}: the sweep in {} has no point {}", side, dir.string(), point));
}

// One side: its name, parameters, main figures (as a sweep row has them) and, for a run, every
// figure of its report.
Json load_side(const std::string& side) {
    const auto at = side.rfind('@');
    if (at != std::string::npos && at + 1 < side.size() &&
        side.find_first_not_of("0123456789", at + 1) == std::string::npos)
        return load_point(side, side.substr(0, at), side.substr(at + 1));
    const fs::path dir(side);
    if (!fs::is_directory(dir)) throw ConfigError(fmt::format("{}: not a run folder nor SWEEP_DIR@POINT", side));
    const Json report = read_object(dir / "report.json", side);
    return {{"name", side},
            {"kind", "run"},
            {"parameters", read_parameters(dir / "config.yaml")},
            {"effective", effective_values(report)},
            {"main", RunSummary::of(report).figures()},
            {"all", all_figures(report)},
            {"legend", object_or_empty(value_at(report, "/statistics"))}};
}

// "125MHz" and "125 MHz" are one value: compared as the parameter reads them.
bool same_parameter(const std::string& key, const std::string& a, const std::string& b) {
    if (a == b) return true;
    const ParamSpec* spec = find_parameter(key);
    if (!spec || spec->kind == ParamKind::choice || spec->kind == ParamKind::text) return false;
    try {
        return parse_value(*spec, a) == parse_value(*spec, b);
    } catch (const std::exception&) {
        return false;
    }
}

Json delta(const Json& ref, const Json& value) {
    if (!ref.is_number() || !value.is_number()) return {{"value", value}};
    const double a = ref.get<double>(), b = value.get<double>();
    Json d = {{"value", value}, {"delta", b - a}};
    d["percent"] = a != 0 ? Json(100 * (b - a) / std::abs(a)) : Json();
    return d;
}

// The unit of each figure of `table` ("main": RunSummary's, "all": the reports' legends).
Json units_of(const Json& table, const std::vector<Json>& sides, const char* kind) {
    Json units = Json::object();
    for (const auto& [key, row] : table.items()) {
        std::string unit = RunSummary::unit_of(key);
        for (const Json& s : sides)
            if (unit.empty() && std::string(kind) == "all") unit = unit_of_path(s["legend"], key);
        units[key] = unit;
    }
    return units;
}

// Figures of `kind` ("main" or "all") on every side; for "all" only those that differ.
Json figure_table(const std::vector<Json>& sides, const char* kind, bool only_differing) {
    std::vector<std::string> keys;
    for (const Json& s : sides)
        for (const auto& [key, v] : s[kind].items())
            if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    Json table = Json::object();
    for (const std::string& key : keys) {
        const Json& ref = sides[0][kind].contains(key) ? sides[0][kind][key] : Json();
        bool differs = false;
        Json row = Json::array();
        for (const Json& s : sides) {
            const Json v = s[kind].contains(key) ? s[kind][key] : Json();
            differs = differs || v != ref;
            row.push_back(delta(ref, v));
        }
        if (differs || !only_differing) table[key] = row;
    }
    return table;
}

std::string cell(const Json& v, const std::string& unit = "") {
    if (v.is_null()) return "-";
    if (v.is_number() || v.is_boolean()) return format_figure(v, unit);
    if (v.is_string()) return v.get<std::string>();
    return v.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string rows_markdown(const Json& table, const Json& units, size_t sides) {
    std::string md;
    for (const auto& [key, row] : table.items()) {
        const std::string unit = units.value(key, "");
        md += "| " + key;
        for (size_t i = 0; i < sides; ++i) {
            const Json& c = row[i];
            md += " | " + cell(c["value"], unit);
            if (i > 0 && c.contains("delta") && c["delta"].get<double>() != 0)
                md += c["percent"].is_null() || unit == "share"
                          ? fmt::format(" ({})", format_change(c["delta"].get<double>(), unit))
                          : fmt::format(" ({}, {:+.2f} %)", format_change(c["delta"].get<double>(), unit),
                                        c["percent"].get<double>());
        }
        md += " |\n";
    }
    return md;
}

// A side's config.yaml is not checked for UTF-8: a byte that is not is written as U+FFFD.
std::string text_of(const Json& c) { return c.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

std::string header(const Json& c) {
    std::string md = "| |";
    std::string rule = "|---|";
    for (const auto& s : c["sides"]) {
        md += " " + s["name"].get<std::string>() + " |";
        rule += "---|";
    }
    return md + "\n" + rule + "\n";
}

}  // namespace

Json compare_runs(const std::vector<std::string>& names) {
    if (names.size() < 2) throw ConfigError("compare: give two or more run folders or sweep points (SWEEP_DIR@N)");
    std::vector<Json> sides;
    for (const std::string& n : names) sides.push_back(load_side(n));
    // Parameters that differ between any two sides.
    std::set<std::string> keys;
    for (const Json& s : sides)
        for (const auto& [k, v] : s["parameters"].items()) keys.insert(k);
    Json parameters = Json::object();
    for (const std::string& k : keys) {
        Json row = Json::array();
        std::vector<std::string> known;  // a sweep point knows only its axes: the rest is not a difference
        for (const Json& s : sides) {
            row.push_back(s["parameters"].contains(k) ? s["parameters"][k] : Json());
            if (row.back().is_string()) known.push_back(row.back().get<std::string>());
        }
        for (const std::string& v : known)
            if (!same_parameter(k, v, known.front())) {
                for (size_t i = 0; i < sides.size(); ++i) row[i] = shown_parameter(k, row[i], sides[i]["effective"]);
                parameters[k] = row;
                break;
            }
    }
    Json budgets = Json::array();
    for (const Json& s : sides) {
        const Json& m = s["main"];
        const auto flag = [&m](const char* key) { return m.contains(key) && m[key].is_boolean() ? m[key] : Json(); };
        budgets.push_back({{"frame_rate", flag("budget_met")},
                           {"power", flag("within_power_budget")},
                           {"fits_fpga", flag("fits")},
                           {"closes_clocks", flag("closes")}});
    }
    Json side_list = Json::array();
    for (const Json& s : sides) side_list.push_back({{"name", s["name"]}, {"kind", s["kind"]}});
    const Json figures = figure_table(sides, "main", false), others = figure_table(sides, "all", true);
    return {{"reference", names[0]},
            {"sides", side_list},
            {"parameters", parameters},
            {"figures", figures},
            {"figure_units", units_of(figures, sides, "main")},
            {"other_figures", others},
            {"other_figure_units", units_of(others, sides, "all")},
            {"budgets", budgets}};
}

std::string compare_markdown(const Json& c) {
    const size_t n = c["sides"].size();
    std::string md = fmt::format("# surfvp compare\n\nAgainst the first, `{}`: each figure with its change and %.\n\n",
                                 c["reference"].get<std::string>());
    md += "## Budgets\n\n" + header(c);
    for (const char* b : {"frame_rate", "power", "fits_fpga", "closes_clocks"}) {
        md += fmt::format("| {} |", b);
        for (const auto& s : c["budgets"])
            md += " " + (s[b].is_null() ? std::string("-") : s[b].get<bool>() ? "met" : "**missed**") + " |";
        md += "\n";
    }
    md += "\n## Parameters that differ\n\n";
    if (c["parameters"].empty())
        md += "None.\n";
    else {
        md += header(c);
        for (const auto& [k, row] : c["parameters"].items()) {
            md += "| " + k;
            for (const auto& v : row) md += " | " + cell(v);
            md += " |\n";
        }
    }
    md += "\n## Figures\n\n" + header(c) + rows_markdown(c["figures"], c["figure_units"], n);
    if (!c["other_figures"].empty())
        md += fmt::format(
            "\n## Every other figure that differs ({})\n\n<details><summary>report.json "
            "paths</summary>\n\n{}{}\n</details>\n",
            c["other_figures"].size(), header(c), rows_markdown(c["other_figures"], c["other_figure_units"], n));
    return md;
}

void check_side(const std::string& side) { load_side(side); }

void write_comparison(const std::string& reference, const std::string& staging, const std::string& published) {
    Json c = compare_runs({reference, staging});
    c["sides"][1]["name"] = published;  // the folder the run is published as, not its staging name
    write_file_atomically((fs::path(staging) / "compare.json").string(), text_of(c));
    write_file_atomically((fs::path(staging) / "compare.md").string(), compare_markdown(c));
}

int compare_command(const CompareOptions& options) {
    const Json c = compare_runs(options.sides);
    if (!options.json.empty()) write_file_atomically(options.json, text_of(c));
    std::fputs(compare_markdown(c).c_str(), stdout);
    return kExitOk;
}

}  // namespace surfvp
