#pragma once
// A block's parameters, declared once beside its Params: each is a scenario key with its
// kind (and so its units), default, range, description and source, bound to the Params
// field it sets. `surfvp params` lists every block's declarations; the platform's wiring
// makes a block's Params from a run's values with ParamTable::make and adds only what the
// block cannot know (which bus it sits on, simulation settings).
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "units.h"

namespace surfvp {

enum class ParamKind { frequency, duration, bits, bytes, cycles, beats, count, real, choice, address, text };

// What a banded parameter is to a review. Only the unknowns are the verdict's doubt; the others
// are what a review can change, shown apart.
enum class ParamRole {
    unknown,   // what the published chip had and the paper does not say: an assumption with a band
    design,    // what an RTL or software change sets, pinned for the published chip by its figures
    workload,  // what the chip is asked to do: keypoints per frame, the threshold
};
inline const char* role_name(ParamRole role) {
    return role == ParamRole::design ? "design" : role == ParamRole::workload ? "workload" : "unknown";
}

struct ParamSpec {
    std::string key;
    ParamKind kind;
    std::string default_value;
    double min;  // in the kind's base unit (Hz, ps, bit, B, cycles, beats)
    double max;
    std::vector<std::string> choices;  // for ParamKind::choice
    std::string description;
    std::string source;  // [S] sourced, [D] derived, [A] assumed, [-] a setting
    // The assumption band (every [A] parameter has one; a few uncertain others too): the
    // plausible low and high values and why. Empty when the parameter has none.
    struct Band {
        std::string low, high, why;
    } band{};
    ParamRole role = ParamRole::unknown;
};

// Range bounds in base units, for declarations.
namespace unit {
constexpr double MHz = 1e6;
constexpr double us = 1e6;  // in ps
constexpr double s = 1e12;  // in ps
constexpr double MiB = 1048576.0;
}  // namespace unit

// A run's values, typed (the scenario's Config); each was checked against its spec.
class ParamValues {
public:
    virtual ~ParamValues() = default;
    virtual Frequency frequency(const std::string& key) const = 0;
    virtual Duration duration(const std::string& key) const = 0;
    virtual unsigned bits(const std::string& key) const = 0;
    virtual Bytes bytes(const std::string& key) const = 0;
    virtual uint64_t cycles(const std::string& key) const = 0;
    virtual unsigned beats(const std::string& key) const = 0;
    virtual uint64_t count(const std::string& key) const = 0;
    virtual double real(const std::string& key) const = 0;
    virtual const std::string& choice(const std::string& key) const = 0;
    virtual const std::string& text(const std::string& key) const = 0;
    virtual uint32_t address(const std::string& key) const = 0;
};

template <typename Params>
struct ParamField {
    ParamSpec spec;
    std::function<void(Params&, const ParamValues&)> apply;
};

namespace param_detail {

inline double number(const ParamSpec& s, const ParamValues& v) {
    switch (s.kind) {
        case ParamKind::bits:
            return v.bits(s.key);
        case ParamKind::cycles:
            return double(v.cycles(s.key));
        case ParamKind::beats:
            return v.beats(s.key);
        case ParamKind::bytes:
            return double(v.bytes(s.key).n);
        case ParamKind::real:
            return v.real(s.key);
        case ParamKind::address:
            return v.address(s.key);
        default:
            return double(v.count(s.key));
    }
}

template <typename T>
void assign(T& target, const ParamSpec& s, const ParamValues& v) {
    if constexpr (std::is_same_v<T, Frequency>)
        target = v.frequency(s.key);
    else if constexpr (std::is_same_v<T, Duration>)
        target = v.duration(s.key);
    else if constexpr (std::is_same_v<T, Bytes>)
        target = v.bytes(s.key);
    else if constexpr (std::is_same_v<T, bool>)
        target = v.choice(s.key) == "on";
    else if constexpr (std::is_same_v<T, std::string>)
        target = s.kind == ParamKind::choice ? v.choice(s.key) : v.text(s.key);
    else if constexpr (std::is_floating_point_v<T>)
        target = T(number(s, v));
    else
        target = T(std::llround(number(s, v)));
}

}  // namespace param_detail

// A parameter that sets `member` of the block's Params (or, for a nested field, what
// `member(params)` returns a reference to).
template <typename Params, typename Member>
ParamField<Params> field(ParamSpec spec, Member member) {
    return {spec, [member, spec](Params& p, const ParamValues& v) {
                if constexpr (std::is_member_object_pointer_v<Member>)
                    param_detail::assign(p.*member, spec, v);
                else
                    param_detail::assign(member(p), spec, v);
            }};
}

// A choice that sets an enum: its names and values, in the order the docs list them.
template <typename Params, typename Enum, typename Member>
ParamField<Params> choice(ParamSpec spec, Member member, std::vector<std::pair<std::string, Enum>> names) {
    spec.kind = ParamKind::choice;
    for (const auto& n : names) spec.choices.push_back(n.first);
    return {spec, [member, names, key = spec.key](Params& p, const ParamValues& v) {
                const std::string& chosen = v.choice(key);
                Enum& target = [&]() -> Enum& {
                    if constexpr (std::is_member_object_pointer_v<Member>)
                        return p.*member;
                    else
                        return member(p);
                }();
                for (const auto& n : names)
                    if (n.first == chosen) target = n.second;
            }};
}

// One block's declarations, in the order `surfvp params` lists them.
template <typename Params>
class ParamTable {
public:
    explicit ParamTable(std::vector<ParamField<Params>> fields) : fields_(std::move(fields)) {}

    std::vector<ParamSpec> specs() const {
        std::vector<ParamSpec> out;
        for (const auto& f : fields_) out.push_back(f.spec);
        return out;
    }
    Params make(const ParamValues& values, Params p = {}) const {
        for (const auto& f : fields_) f.apply(p, values);
        return p;
    }

private:
    std::vector<ParamField<Params>> fields_;
};

}  // namespace surfvp
