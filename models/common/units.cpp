#include "units.h"

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <limits>
#include <utility>
#include <vector>

namespace surfvp {
namespace {

struct Unit {
    const char* name;
    double scale;  // value in the kind's base unit per one of this unit
};

struct Kind {
    const char* what;  // "a frequency"
    std::vector<Unit> units;
    bool integer;  // the result must be a whole number of base units
};

const Kind& kind(UnitKind k) {
    static const Kind frequency{"a frequency", {{"Hz", 1}, {"kHz", 1e3}, {"MHz", 1e6}, {"GHz", 1e9}}, false};
    static const Kind duration{"a duration", {{"ps", 1}, {"ns", 1e3}, {"us", 1e6}, {"ms", 1e9}, {"s", 1e12}}, true};
    static const Kind bits{"a width in bits", {{"bit", 1}, {"bits", 1}}, true};
    static const Kind bytes{
        "a size in bytes", {{"B", 1}, {"KiB", 1024.0}, {"MiB", 1048576.0}, {"GiB", 1073741824.0}}, true};
    static const Kind cycles{"a number of clock cycles", {{"cycle", 1}, {"cycles", 1}}, true};
    static const Kind beats{"a number of bus beats", {{"beat", 1}, {"beats", 1}}, true};
    switch (k) {
        case UnitKind::frequency:
            return frequency;
        case UnitKind::duration:
            return duration;
        case UnitKind::bits:
            return bits;
        case UnitKind::bytes:
            return bytes;
        case UnitKind::cycles:
            return cycles;
        case UnitKind::beats:
            return beats;
    }
    return frequency;
}

std::string unit_list(const Kind& k) {
    std::string out;
    for (const auto& u : k.units) out += (out.empty() ? "" : ", ") + std::string(u.name);
    return out;
}

// "<number> <unit>" (the space is optional) -> value in the kind's base unit.
double parse(const std::string& text, UnitKind which) {
    const Kind& k = kind(which);
    const char* begin = text.c_str();
    char* end = nullptr;
    double number = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(number))
        throw UnitError(fmt::format("'{}' is not {}: expected a number and a unit ({})", text, k.what, unit_list(k)));
    std::string unit(end);
    unit.erase(0, unit.find_first_not_of(' '));
    unit.erase(unit.find_last_not_of(' ') + 1);
    if (unit.empty()) throw UnitError(fmt::format("'{}' has no unit: {} needs one of {}", text, k.what, unit_list(k)));
    for (const auto& u : k.units) {
        if (unit != u.name) continue;
        double value = number * u.scale;
        if (value < 0) throw UnitError(fmt::format("'{}' is negative: {} cannot be", text, k.what));
        if (k.integer && std::abs(value - std::round(value)) > 1e-6)
            throw UnitError(fmt::format("'{}' is not a whole number of {}", text, k.units.front().name));
        return k.integer ? std::round(value) : value;
    }
    throw UnitError(fmt::format("'{}' has the wrong unit '{}': {} takes {}", text, unit, k.what, unit_list(k)));
}

// The largest unit in which the value is a whole number; otherwise the largest unit it is at
// least one of, printed so that it parses back (units.h says how exactly).
std::string format(double value, UnitKind which) {
    const Kind& k = kind(which);
    for (auto it = k.units.rbegin(); it != k.units.rend(); ++it) {
        double scaled = value / it->scale;
        // A frequency (durations and sizes: format_whole) as a whole number of a unit when
        // within 1e-9 of one, while it fits an integer (a frequency has no upper bound).
        if (scaled >= 1 && scaled < 0x1p64 && std::abs(scaled - std::round(scaled)) <= 1e-9)
            return fmt::format("{} {}", static_cast<uint64_t>(std::round(scaled)), it->name);
    }
    for (auto it = k.units.rbegin(); it != k.units.rend(); ++it)
        if (value / it->scale >= 1) return fmt::format("{} {}", value / it->scale, it->name);
    return fmt::format("{} {}", value, k.units.front().name);
}

// A parsed value as the integer type that holds it: a value the type cannot hold is out of
// range, never wrapped or truncated.
template <typename T>
T fitting(double value, const std::string& text) {
    // Below 2^digits: double(max) of a 64-bit type rounds up to 2^64, which does not fit.
    if (!(value < std::ldexp(1.0, std::numeric_limits<T>::digits)))  // also catches NaN
        throw UnitError(fmt::format("'{}' is out of range: at most {} fits", text, std::numeric_limits<T>::max()));
    return static_cast<T>(value);
}

}  // namespace

Frequency parse_frequency(const std::string& text) {
    Frequency f{parse(text, UnitKind::frequency)};
    if (f.hz <= 0) throw UnitError(fmt::format("'{}': a frequency must be above zero", text));
    return f;
}
Duration parse_duration(const std::string& text) {
    return Duration{fitting<uint64_t>(parse(text, UnitKind::duration), text)};
}
unsigned parse_bits(const std::string& text) { return fitting<unsigned>(parse(text, UnitKind::bits), text); }
Bytes parse_bytes(const std::string& text) { return Bytes{fitting<uint64_t>(parse(text, UnitKind::bytes), text)}; }
uint64_t parse_cycles(const std::string& text) { return fitting<uint64_t>(parse(text, UnitKind::cycles), text); }
unsigned parse_beats(const std::string& text) { return fitting<unsigned>(parse(text, UnitKind::beats), text); }

std::string format_frequency(Frequency f) { return format(f.hz, UnitKind::frequency); }
namespace {

// A whole number of picoseconds or bytes in the largest unit that divides it, in integers: a
// double's 53 bits would round 18444674407370954752 ps to a "whole" 18444674407370956 ns.
std::string format_whole(uint64_t value, UnitKind which) {
    const Kind& k = kind(which);
    for (auto it = k.units.rbegin(); it != k.units.rend(); ++it) {
        const auto scale = static_cast<uint64_t>(it->scale);
        if (value >= scale && value % scale == 0) return fmt::format("{} {}", value / scale, it->name);
    }
    return fmt::format("{} {}", value, k.units.front().name);
}

}  // namespace

std::string format_duration(Duration d) { return format_whole(d.ps, UnitKind::duration); }
std::string format_bytes(Bytes b) { return format_whole(b.n, UnitKind::bytes); }

}  // namespace surfvp
