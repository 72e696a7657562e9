#pragma once
// The assumption band as a tornado chart (SVG, self-contained): one row per assumption, the
// largest effect first, a bar from the reference frame rate to the rate at the assumption's
// low and one to its high, with the reference and the budget as vertical lines.
#include <nlohmann/json.hpp>
#include <string>

namespace surfvp {

// `band` is the verdict's band section (verdict.cpp); budget 0 draws no budget line.
std::string tornado_svg(const nlohmann::ordered_json& band, double budget, size_t rows = 15);

}  // namespace surfvp
