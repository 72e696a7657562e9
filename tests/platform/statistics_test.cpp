// The statistics registry's one path to the reports: paths become the tree of report.json,
// numbered instances arrays, each kind its JSON type, and every figure a Markdown row.
#include <gtest/gtest.h>

#include "platform/report/statistics_json.h"

namespace surfvp {
namespace {

TEST(Statistics, TreeLegendAndMarkdownFromOneRegistry) {
    Statistics registry;
    uint64_t frames = 3, level = 17;
    const sc_core::sc_time busy(250, sc_core::SC_MS);
    for (int k = 0; k < 2; ++k) {
        const Statistics::Scope s = registry.scope("fhg." + std::to_string(k));
        s.count(
            "frames", [&, k] { return frames + uint64_t(k); }, "frames", "frames ended");
        s.high_water(
            "maxima_fifo_high_water", [&] { return level; }, "entries", "highest level");
        s.share(
            "utilisation", [&] { return busy; }, "busy over the run");
    }
    const Statistics::Scope bus = registry.scope("buses.plb2");
    bus.time(
        "busy_s", [&] { return busy; }, "carrying bursts");
    bus.text(
        "arbitration", [] { return std::string("round_robin"); }, "the arbitration");
    bus.histogram(
        "waits",
        [] {
            return std::vector<std::pair<std::string, uint64_t>>{{"0", 5}, {"1", 2}};
        },
        "bursts", "by wait");
    const auto tree = statistics_tree(registry, 0.5);
    ASSERT_TRUE(tree["fhg"].is_array());
    EXPECT_EQ(tree["fhg"].size(), 2u);
    EXPECT_EQ(tree["fhg"][1]["frames"].get<uint64_t>(), 4u);
    EXPECT_TRUE(tree["fhg"][0]["frames"].is_number_unsigned());
    EXPECT_DOUBLE_EQ(tree["fhg"][0]["utilisation"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(tree["buses"]["plb2"]["busy_s"].get<double>(), 0.25);
    EXPECT_EQ(tree["buses"]["plb2"]["arbitration"], "round_robin");
    EXPECT_EQ(tree["buses"]["plb2"]["waits"]["1"].get<uint64_t>(), 2u);
    nlohmann::ordered_json report = tree;
    report["statistics"] = statistics_legend(registry);
    EXPECT_EQ(report["statistics"]["fhg.1.maxima_fifo_high_water"]["kind"], "high-water");
    const std::string md = statistics_markdown(report);
    EXPECT_NE(md.find("| `fhg.1.frames` | 4 | frames | count | frames ended |"), std::string::npos) << md;
    EXPECT_NE(md.find("| `fhg.0.utilisation` | 50.0 % |"), std::string::npos) << md;
    EXPECT_NE(md.find("| `buses.plb2.waits` | 0: 5, 1: 2 | bursts | histogram |"), std::string::npos) << md;
}

}  // namespace
}  // namespace surfvp
