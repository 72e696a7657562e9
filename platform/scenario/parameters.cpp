#include "platform/scenario/parameters.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <limits>

#include "models/common/units.h"
#include "models/plb/plb_bus.h"

namespace surfvp {

const std::vector<PlbDeclaration>& plb_declarations() {
    static const std::vector<PlbDeclaration> buses{
        {"plb1", PlbBus::parameter_table("plb1", "128 bit", "[S] ML507 DTS: mplb-dwidth = 0x80",
                                         "PLB1 (CPU and register slaves)")},
        {"plb2", PlbBus::parameter_table(
                     "plb2", "128 bit",
                     "[A] the paper: PLB2 \"has accordingly increased capacity\" (Fig. 3 lost); 64 bit would do",
                     "PLB2 (IP DMA traffic)")}};
    return buses;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// Both return infinity for a number too large for any type, so that the range check calls it
// out of range (never wrapped, never "not a number").
double parse_address(const std::string& text) {
    std::string digits;
    for (char c : text)
        if (c != '_') digits += c;
    size_t used = 0;
    unsigned long long value = 0;
    try {
        value = std::stoull(digits, &used, 0);
    } catch (const std::out_of_range&) {
        return kInf;
    } catch (const std::exception&) {
        used = 0;
    }
    if (digits.empty() || used != digits.size() || digits[0] == '-')
        throw UnitError(fmt::format("'{}' is not an address: expected a number such as 0x0010_0000", text));
    return double(value);
}

double parse_plain(const std::string& text, bool integer) {
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(begin, &end);
    const bool too_large = errno == ERANGE && std::isinf(value);  // "1e400": a number, beyond any double
    if (end == begin || size_t(end - begin) != text.size() || std::isspace(static_cast<unsigned char>(text[0])) ||
        (!std::isfinite(value) && !too_large))
        throw UnitError(fmt::format("'{}' is not a {}", text, integer ? "whole number" : "finite number"));
    if (integer && !too_large && value != std::floor(value))
        throw UnitError(fmt::format("'{}' is not a whole number", text));
    return value;
}

}  // namespace

std::string format_value(const ParamSpec& spec, double value) {
    switch (spec.kind) {
        case ParamKind::frequency:
            return format_frequency(Frequency{value});
        case ParamKind::duration:
            return format_duration(Duration{uint64_t(value)});
        case ParamKind::bits:
            return fmt::format("{} bit", uint64_t(value));
        case ParamKind::bytes:
            return format_bytes(Bytes{uint64_t(value)});
        case ParamKind::cycles:
            return fmt::format("{} cycles", uint64_t(value));
        case ParamKind::beats:
            return fmt::format("{} beats", uint64_t(value));
        case ParamKind::address:
            return fmt::format("{:#x}", uint64_t(value));
        case ParamKind::count:
            return fmt::format("{}", uint64_t(value));
        default:
            return fmt::format("{}", value);
    }
}

std::vector<const ParamSpec*> band_parameters() {
    std::vector<const ParamSpec*> out;
    for (const ParamSpec& p : parameter_table())
        if (!p.band.low.empty()) out.push_back(&p);
    return out;
}

const ParamSpec* find_parameter(std::string_view key) {
    for (const ParamSpec& p : parameter_table())
        if (p.key == key) return &p;
    return nullptr;
}

std::string closest_parameter(std::string_view key) {
    std::string best;
    size_t best_distance = 4;  // farther than three edits is no longer a typo
    for (const ParamSpec& p : parameter_table()) {
        const size_t d = edit_distance(key, p.key);
        if (d < best_distance) {
            best_distance = d;
            best = p.key;
        }
    }
    return best;
}

double parse_value(const ParamSpec& spec, const std::string& text) {
    double value = 0;
    switch (spec.kind) {
        case ParamKind::frequency:
            value = parse_frequency(text).hz;
            break;
        case ParamKind::duration:
            value = double(parse_duration(text).ps);
            break;
        case ParamKind::bits:
            value = parse_bits(text);
            break;
        case ParamKind::bytes:
            value = double(parse_bytes(text).n);
            break;
        case ParamKind::cycles:
            value = double(parse_cycles(text));
            break;
        case ParamKind::beats:
            value = parse_beats(text);
            break;
        case ParamKind::count:
            value = parse_plain(text, true);
            break;
        case ParamKind::real:
            value = parse_plain(text, false);
            break;
        case ParamKind::address:
            value = parse_address(text);
            break;
        case ParamKind::text:
            return 0;
        case ParamKind::choice:
            if (std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end())
                throw UnitError(fmt::format("'{}' is not one of: {}", text, fmt::join(spec.choices, ", ")));
            return 0;
    }
    if (!(value >= spec.min && value <= spec.max))  // NaN is out of every range
        throw UnitError(fmt::format("'{}' is out of range: {} must be between {} and {}", text, spec.key,
                                    format_value(spec, spec.min), format_value(spec, spec.max)));
    return value;
}

std::string describe_kind(const ParamSpec& spec) {
    switch (spec.kind) {
        case ParamKind::frequency:
            return "frequency (Hz, kHz, MHz, GHz)";
        case ParamKind::duration:
            return "duration (ps, ns, us, ms, s)";
        case ParamKind::bits:
            return "width (bit)";
        case ParamKind::bytes:
            return "size (B, KiB, MiB, GiB)";
        case ParamKind::cycles:
            return "clock cycles (cycles)";
        case ParamKind::beats:
            return "bus beats (beats)";
        case ParamKind::count:
            return "whole number";
        case ParamKind::real:
            return "number";
        case ParamKind::address:
            return "address";
        case ParamKind::choice:
            return fmt::format("one of {}", fmt::join(spec.choices, ", "));
        case ParamKind::text:
            return "text";
    }
    return "";
}

std::string parameters_markdown() {
    std::string out =
        "# surfvp parameters\n\n"
        "Every parameter a scenario can set, with its default and where the default comes from:\n"
        "**[S]** sourced, **[D]** derived, **[A]** assumed (the reason follows), **[-]** a choice, not a\n"
        "fact. Generated by `surfvp params`; a test keeps this file equal to its output. A block's parameters are\n"
        "declared beside its Params (`models/<block>/*_params.cpp`), the platform's own beside the code\n"
        "that reads each (platform/catalog.cpp gathers them).\n\n"
        "| key | default | range | kind | what it is | source |\n|---|---|---|---|---|---|\n";
    for (const ParamSpec& p : parameter_table()) {
        std::string range = p.kind == ParamKind::choice || p.kind == ParamKind::text
                                ? ""
                                : fmt::format("{} .. {}", format_value(p, p.min), format_value(p, p.max));
        out += fmt::format("| `{}` | `{}` | {} | {} | {} | {} |\n", p.key, p.default_value, range, describe_kind(p),
                           p.description, p.source);
    }
    out +=
        "\n## Assumption band\n\n"
        "Every assumed value, and a few uncertain others, with a plausible low and high, and its role: an\n"
        "**unknown** about the published chip (the verdict samples the unknowns jointly over their bands,\n"
        "and re-simulates each at its low and its high for the tornado), a **design** choice an RTL or\n"
        "software change sets, or the **workload**; the verdict shows design and workload apart, as what a\n"
        "review can change (`verdict.band`).\n\n"
        "| key | role | default | low | high | why |\n|---|---|---|---|---|---|\n";
    for (const ParamSpec* p : band_parameters())
        out += fmt::format("| `{}` | {} | `{}` | `{}` | `{}` | {} |\n", p->key, role_name(p->role), p->default_value,
                           p->band.low, p->band.high, p->band.why);
    return out;
}

}  // namespace surfvp
