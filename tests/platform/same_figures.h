#pragma once
// Two runs' report.json, figure by figure: the same run made another way (a speed setting,
// another datapath model) must report the same.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace surfvp::test {

// Every number and text of report.json `a` against `b` (relative `tolerance` for numbers), but the fields
// that name themselves wall-clock or simulation figures, and the outputs' list; the paths
// where they differ.
inline void compare_figures(const nlohmann::json& a, const nlohmann::json& b, const std::set<std::string>& skip,
                            double tolerance, const std::string& path, std::vector<std::string>& differences) {
    if (a.is_object()) {
        for (const auto& [key, value] : a.items()) {
            if (path.empty() && skip.count(key)) continue;
            if (!b.contains(key))
                differences.push_back(path + "/" + key + " missing");
            else
                compare_figures(value, b[key], skip, tolerance, path + "/" + key, differences);
        }
    } else if (a.is_array()) {
        if (a.size() != b.size())
            differences.push_back(path + " sizes differ");
        else
            for (size_t i = 0; i < a.size(); ++i)
                compare_figures(a[i], b[i], skip, tolerance, path + "/" + std::to_string(i), differences);
    } else if (a.is_number() && b.is_number()) {
        const double x = a.get<double>(), y = b.get<double>();
        if (std::abs(x - y) > tolerance * std::max({std::abs(x), std::abs(y), 1e-12}))
            differences.push_back(path + ": " + a.dump() + " vs " + b.dump());
    } else if (a != b) {
        differences.push_back(path + ": " + a.dump() + " vs " + b.dump());
    }
}

inline void expect_same_figures(const nlohmann::json& a, const nlohmann::json& b, const std::string& what,
                                double tolerance = 1e-9) {
    std::set<std::string> skip{"wall_clock_fields", "simulation_fields", "outputs"};
    for (const char* list :
         {"wall_clock_fields", "simulation_fields"})  // direct mode's report has no simulation_fields
        for (const auto& f : a.value(list, nlohmann::json::array())) skip.insert(f.get<std::string>());
    std::vector<std::string> differences;
    compare_figures(a, b, skip, tolerance, "", differences);
    EXPECT_TRUE(differences.empty()) << what << ": " << differences.size()
                                     << " figures differ, first: " << differences[0];
}

}  // namespace surfvp::test
