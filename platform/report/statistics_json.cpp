#include "statistics_json.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace surfvp {

namespace {

std::vector<std::string> levels(const std::string& path) {
    std::vector<std::string> out;
    size_t from = 0;
    for (size_t dot; (dot = path.find('.', from)) != std::string::npos; from = dot + 1)
        out.push_back(path.substr(from, dot - from));
    out.push_back(path.substr(from));
    return out;
}

nlohmann::ordered_json value_of(const Statistic& s, double elapsed_s) {
    switch (s.kind) {
        case StatKind::text:
            return s.text();
        case StatKind::histogram: {
            nlohmann::ordered_json bins = nlohmann::ordered_json::object();
            for (const auto& [name, n] : s.bins()) bins[name] = n;
            return bins;
        }
        case StatKind::series:
            return {{"bin_s", double(s.series->bin_ps()) * 1e-12}, {"values", s.series->values()}};
        case StatKind::count:
        case StatKind::bytes:
        case StatKind::high_water:
            return uint64_t(std::llround(s.number(elapsed_s)));
        case StatKind::value: {
            const double v = s.number(elapsed_s);
            if (v == std::floor(v) && std::fabs(v) < 9e15) return int64_t(v);
            return v;
        }
        default:
            return s.number(elapsed_s);
    }
}

// Objects keyed 0, 1, ... n-1 are a block's instances: an array, as the accelerator pairs.
void number_instances(nlohmann::ordered_json& node) {
    if (!node.is_object()) return;
    for (auto& [key, child] : node.items()) number_instances(child);
    size_t i = 0;
    for (const auto& [key, child] : node.items())
        if (key != std::to_string(i++)) return;
    if (node.empty()) return;
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (auto& [key, child] : node.items()) list.push_back(child);
    node = list;
}

// The node at `path` (numbered levels index arrays), or nullptr.
template <typename Json>
Json* find(Json& report, const std::string& path) {
    Json* node = &report;
    for (const std::string& level : levels(path)) {
        if (node->is_array()) {
            const size_t i = std::stoul(level);
            if (i >= node->size()) return nullptr;
            node = &(*node)[i];
        } else if (node->is_object() && node->contains(level)) {
            node = &(*node)[level];
        } else {
            return nullptr;
        }
    }
    return node;
}

std::string cell(const nlohmann::ordered_json& v, const std::string& kind) {
    if (v.is_string()) return v.get<std::string>();
    if (kind == "series") {
        double peak = 0;
        for (const auto& x : v["values"]) peak = std::max(peak, x.get<double>());
        return fmt::format("{} bins of {:g} ms, peak {:g} (report.html)", v["values"].size(),
                           v["bin_s"].get<double>() * 1e3, peak);
    }
    if (v.is_object()) {
        std::string bins;
        for (const auto& [name, n] : v.items())
            bins += fmt::format("{}{}: {}", bins.empty() ? "" : ", ", name, n.dump());
        return bins;
    }
    if (kind == "ratio") return fmt::format("{:.1f} %", 100 * v.get<double>());
    if (v.is_number_float()) return fmt::format("{:.6g}", v.get<double>());
    return v.dump();
}

}  // namespace

// The paths' shape first (instances numbered), then the values: a histogram's bins are a
// value, never instances.
nlohmann::ordered_json statistics_tree(const Statistics& statistics, double elapsed_s) {
    nlohmann::ordered_json tree = nlohmann::ordered_json::object();
    for (const Statistic& s : statistics.all()) {
        nlohmann::ordered_json* node = &tree;
        for (const std::string& level : levels(s.path)) node = &(*node)[level];
    }
    number_instances(tree);
    for (const Statistic& s : statistics.all()) *find(tree, s.path) = value_of(s, elapsed_s);
    return tree;
}

nlohmann::ordered_json statistics_legend(const Statistics& statistics) {
    nlohmann::ordered_json legend = nlohmann::ordered_json::object();
    for (const Statistic& s : statistics.all())
        legend[s.path] = {{"kind", stat_kind_name(s.kind)}, {"unit", s.unit}, {"meaning", s.meaning}};
    return legend;
}

std::string statistics_markdown(const nlohmann::ordered_json& report) {
    if (!report.contains("statistics")) return "";
    std::string md = "| statistic | value | unit | kind | meaning |\n| --- | --- | --- | --- | --- |\n";
    for (const auto& [path, about] : report["statistics"].items()) {
        const nlohmann::ordered_json* v = find(report, path);
        if (!v) continue;
        const std::string kind = about["kind"];
        md += fmt::format("| `{}` | {} | {} | {} | {} |\n", path, cell(*v, kind), about["unit"].get<std::string>(),
                          kind, about["meaning"].get<std::string>());
    }
    return md;
}

}  // namespace surfvp
