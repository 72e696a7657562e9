// Fuzz target: the unit parsers (models/common/units.h) and the parameter parse
// (platform/scenario/parameters.h: parse_value, Config::set).
//
// Input: one selector byte, then the text to parse. The selector picks one of the six unit
// parsers, or a parameter of the table (parse_value on its kind, with its range).
//
// Expected answer to bad text: UnitError (ConfigError from Config::set). Any other exception,
// a crash or a sanitizer report is a bug, and so is a broken promise of units.h or
// parameters.h on text that parses:
//   - the canonical text of a value (format_frequency, format_duration, format_bytes,
//     format_value) parses back to the same value: exactly, but for a frequency to units.h's
//     relative 1e-9;
//   - a parameter's value lies in its range.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <string>

#include "fuzz_support.h"
#include "models/common/units.h"
#include "platform/scenario/config.h"
#include "platform/scenario/parameters.h"

namespace {
using namespace surfvp;

// `relative`: the tolerance, 0 for exactly.
template <typename T>
void same(const std::string& text, const std::string& canonical, T parsed, T again, double relative = 0) {
    const double a = double(parsed), b = double(again);
    if (!(parsed == again || std::abs(a - b) <= relative * std::max(std::abs(a), std::abs(b))))
        fuzz::bug("'" + text + "' reads as " + fmt::format("{}", parsed) + ", its canonical text '" + canonical +
                  "' as " + fmt::format("{}", again));
}

void unit_parser(unsigned which, const std::string& text) {
    switch (which) {
        case 0: {
            const Frequency f = parse_frequency(text);
            const std::string canonical = format_frequency(f);
            same(text, canonical, f.hz, parse_frequency(canonical).hz, 1e-9);
            break;
        }
        case 1: {
            const Duration d = parse_duration(text);
            const std::string canonical = format_duration(d);
            same(text, canonical, d.ps, parse_duration(canonical).ps);
            break;
        }
        case 2: {
            const Bytes b = parse_bytes(text);
            const std::string canonical = format_bytes(b);
            same(text, canonical, b.n, parse_bytes(canonical).n);
            break;
        }
        case 3:
            parse_bits(text);
            break;
        case 4:
            parse_cycles(text);
            break;
        default:
            parse_beats(text);
            break;
    }
}

void parameter(const ParamSpec& spec, const std::string& text) {
    const double value = parse_value(spec, text);
    if (spec.kind == ParamKind::choice || spec.kind == ParamKind::text) return;
    if (!(value >= spec.min && value <= spec.max))
        fuzz::bug(fmt::format("{} = '{}' reads as {}, outside its range", spec.key, text, value));
    const std::string canonical = format_value(spec, value);
    same(text, canonical, value, parse_value(spec, canonical), spec.kind == ParamKind::frequency ? 1e-9 : 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fuzz::Bytes in(data, size);
    const unsigned selector = in.u8();
    const std::string text(in.rest());
    const std::vector<ParamSpec>& table = parameter_table();
    try {
        if (selector < 6) {
            unit_parser(selector, text);
        } else {
            const ParamSpec& spec = table[(selector - 6) % table.size()];
            parameter(spec, text);
            Config config;
            config.set(spec.key, text, "--set");
        }
    } catch (const UnitError&) {
        // the parsers' answer to text that is not a value of the kind
    } catch (const ConfigError&) {
        // Config::set's answer, naming the key
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
