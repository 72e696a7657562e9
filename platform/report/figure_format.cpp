#include "platform/report/figure_format.h"

#include <cmath>
#include <fmt/format.h>

namespace surfvp {
namespace {

struct Scaled {
    double value;
    const char* unit;
};

// The largest of `steps` (factor, name; largest first) that leaves |v| at 1 or more.
template <size_t N>
Scaled scale(double v, const Scaled (&steps)[N]) {
    for (const Scaled& s : steps)
        if (std::abs(v) >= s.value) return {v / s.value, s.unit};
    return {v / steps[N - 1].value, steps[N - 1].unit};
}

Scaled scaled(double v, const std::string& unit) {
    static const Scaled hz[] = {{1e9, "GHz"}, {1e6, "MHz"}, {1e3, "kHz"}, {1, "Hz"}};
    static const Scaled s[] = {{1, "s"}, {1e-3, "ms"}, {1e-6, "µs"}, {1e-9, "ns"}};
    static const Scaled bytes[] = {{1073741824.0, "GiB"}, {1048576.0, "MiB"}, {1024.0, "KiB"}, {1, "B"}};
    static const Scaled rate[] = {{1e9, "GB/s"}, {1e6, "MB/s"}, {1e3, "kB/s"}, {1, "B/s"}};
    if (v == 0) return {0, unit == "us" ? "µs" : unit.c_str()};
    if (unit == "Hz") return scale(v, hz);
    if (unit == "s") return scale(v, s);
    if (unit == "ms") return scale(v * 1e-3, s);
    if (unit == "us") return scale(v * 1e-6, s);
    if (unit == "B") return scale(v, bytes);
    if (unit == "B/s") return scale(v, rate);
    return {v, unit.c_str()};
}

std::string number(double v) {
    if ((v == std::floor(v) || std::abs(v) >= 1e4) && std::abs(v) < 1e15) return fmt::format("{:.0f}", v);
    return fmt::format("{:.4g}", v);
}

}  // namespace

std::string format_figure(const nlohmann::ordered_json& value, const std::string& unit) {
    if (value.is_null()) return "-";
    if (value.is_boolean()) return value.get<bool>() ? "yes" : "no";
    if (value.is_string()) return value.get<std::string>();
    if (!value.is_number()) return value.dump();
    const double v = value.get<double>();
    if (unit == "share") return fmt::format("{:.1f} %", 100 * v);
    const Scaled s = scaled(v, unit);
    const std::string n = number(s.value);
    return *s.unit ? n + " " + s.unit : n;
}

std::string format_change(double delta, const std::string& unit) {
    if (unit == "share") return fmt::format("{:+.1f} points", 100 * delta);
    const std::string text = format_figure(nlohmann::ordered_json(std::abs(delta)), unit);
    return (delta < 0 ? "-" : "+") + text;
}

}  // namespace surfvp
