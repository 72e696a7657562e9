#pragma once
// The VP beside the chip the paper measured (docs/architecture.md#principles, 11). The paper states a few
// figures about its own chip; each is a measurement of real hardware, so a scenario at the
// paper's settings must reproduce it, or the report says which assumption keeps them apart:
// - about 10 frames/s at 1024x768, with around 100 descriptors per image (§I and its note 1;
//   §V "about 10 FPS");
// - a basic MasterController script about 11 % slower per determinant block than the
//   "optimal state" (§III-C and its note 4: the read buses carry no idle cycles waiting for
//   busy TripleMACs);
// - less than 10 W for the whole device (§I, §V);
// - Table II's distinguishability, FPGA against CPU (§IV-A): measured by `surfvp table2`, not
//   by a timing run.
// "About", "approximately" and "around" are read as within 10 % of the stated value; "less
// than" as a bound (docs/correlation.md).
#include <nlohmann/json.hpp>
#include <string>

namespace surfvp {

// The paper's figures about its chip, and the share within which "about" holds.
namespace paper {
constexpr double kFps = 10, kDescriptors = 100, kOverhead = 0.11, kWatts = 10, kAbout = 0.10;
constexpr int kWidth = 1024, kHeight = 768;
}  // namespace paper

// One row per figure: {figure, paper, paper_says, low, high, vp, difference, within, note}.
// `within` is null where the run cannot be compared (another image size, keypoint count or a
// figure the run does not measure), and `note` says why. Reads a SURF run's report.
nlohmann::ordered_json correlation_json(const nlohmann::ordered_json& report);

// The table as report.md shows it, and as report.html does.
std::string correlation_markdown(const nlohmann::ordered_json& correlation);
std::string correlation_html(const nlohmann::ordered_json& correlation);

}  // namespace surfvp
