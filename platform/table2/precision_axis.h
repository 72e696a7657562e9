#pragma once
// A study's axis as `--axis KEY=V1,V2,...` gives it: a parameter and the values the study
// tries (docs/precision.md, docs/quality_budget.md).
#include <string>
#include <vector>

namespace surfvp {

struct PrecisionAxis {
    std::string key;
    std::vector<std::string> values;
};

// Throws ConfigError naming the option when the text is not KEY=VALUE,..., the key is not a
// parameter, or a value is empty. The values are checked against the parameter when the
// study applies them (before any point runs).
PrecisionAxis parse_precision_axis(const std::string& text);

// The --axis options, one per key (a key given twice is refused, naming both), or `defaults`
// when none is given.
std::vector<PrecisionAxis> parse_axes(const std::vector<std::string>& given, std::vector<PrecisionAxis> defaults);

}  // namespace surfvp
