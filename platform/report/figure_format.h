#pragma once
// A figure as a person reads it, through its unit: a clock in MHz, a time in ms or µs, bytes
// in KiB or MiB, a rate in MB/s, a share in percent, with four significant digits. The
// statistics registry's units (report.json's legend) and RunSummary's figure units are the
// inputs; a sweep's tables and compare's show what this gives.
#include <string>

#include <nlohmann/json.hpp>

namespace surfvp {

// `value` in `unit` ("Hz", "s", "ms", "B", "B/s", "share", "frames/s", "W", ...; "" none): a
// number with its unit scaled, a boolean as yes/no, text as it is, null as "-".
std::string format_figure(const nlohmann::ordered_json& value, const std::string& unit);

// A change of `delta` in `unit`, signed ("+1.25 ms", "-3.1 points" for a share).
std::string format_change(double delta, const std::string& unit);

}  // namespace surfvp
