#include "platform/compare/run_figures.h"

#include <set>
#include <string>

#include "platform/report/json_input.h"

namespace surfvp {
using Json = nlohmann::ordered_json;

namespace {

// The report's numeric figures by path, leaving out what is not a figure of the chip (wall
// clock, the legend, per-frame rows, time series, the workload's own section, the verdict's).
// The recursion is bounded by parse_json's depth limit.
void flatten(const Json& j, const std::string& path, const std::set<std::string>& skip, Json& out) {
    if (j.is_object()) {
        for (const auto& [key, value] : j.items())
            if (!skip.count(key)) flatten(value, path.empty() ? key : path + "." + key, skip, out);
    } else if (j.is_number()) {
        out[path] = j;
    }
}

}  // namespace

Json all_figures(const Json& report) {
    std::set<std::string> skip = {"statistics", "per_frame", "workload",    "verdict",          "checks",
                                  "outputs",    "scenario",  "busy_series", "line_fifo_series", "maxima_fifo_series",
                                  "schedules"};
    for (const char* legend : {"/wall_clock_fields", "/simulation_fields"})
        if (const Json& fields = value_at(report, legend); fields.is_array())
            for (const auto& f : fields)
                if (f.is_string()) skip.insert(f.get<std::string>());
    Json all = Json::object();
    flatten(report, "", skip, all);
    return all;
}

}  // namespace surfvp
