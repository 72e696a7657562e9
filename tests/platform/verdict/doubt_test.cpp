// The verdict's joint doubt: the design samples every unknown over its band in a Latin
// hypercube, the same points for the same seed; the distribution and the probability of meeting
// the budget are the points' own; the sensitivity finds the unknown the rate depends on, alone
// and through an interaction, and gives the others none.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <set>

#include "platform/scenario/config.h"
#include "platform/scenario/parameters.h"
#include "platform/verdict/doubt.h"

namespace surfvp {
namespace {
using Json = nlohmann::ordered_json;

std::vector<Unknown> three_unknowns() {
    // Two clocks and a choice, as unknowns_of makes them from the banded parameters.
    const Config config;
    std::vector<const ParamSpec*> banded{find_parameter("fhg.clock"), find_parameter("cpu.clock"),
                                         find_parameter("fhg.line_fifo")};
    return unknowns_of(banded, config);
}

TEST(Doubt, UnknownsSpanTheirBandAndTheDefault) {
    const auto u = three_unknowns();
    ASSERT_EQ(u.size(), 3u);
    EXPECT_DOUBLE_EQ(u[0].low, 90e6);
    EXPECT_DOUBLE_EQ(u[0].high, 125e6);
    EXPECT_TRUE(u[2].values == std::vector<std::string>({"tdp", "tdp_x2", "banked"}));
    // Design choices and the workload are not unknowns.
    const Config config;
    EXPECT_TRUE(unknowns_of({find_parameter("fhg.bus_word"), find_parameter("surf.target_keypoints")}, config).empty());
}

TEST(Doubt, TheDesignIsALatinHypercubeAndRepeatable) {
    const auto u = three_unknowns();
    const JointDesign d = joint_design(u, 50, 1);
    ASSERT_EQ(d.unit.size(), 50u);
    for (size_t k = 0; k < u.size(); ++k) {
        std::set<int> strata;
        for (const auto& point : d.unit) strata.insert(int(point[k] * 50));
        EXPECT_EQ(strata.size(), 50u) << "each of the 50 strata once, unknown " << k;
    }
    std::map<std::string, int> fifo;
    for (const auto& sets : d.sets) {
        const double mhz = std::stod(sets[0].second);
        EXPECT_GE(mhz, 90.0);
        EXPECT_LE(mhz, 125.0);
        ++fifo[sets[2].second];
    }
    EXPECT_EQ(fifo.size(), 3u);
    for (const auto& [value, n] : fifo) EXPECT_NEAR(n, 50.0 / 3, 1.0) << value;
    EXPECT_EQ(joint_design(u, 50, 1).sets, d.sets);
    EXPECT_NE(joint_design(u, 50, 2).sets, d.sets);
}

// Points from a known chip: the FHG allows 9.6 frames/s per 100 MHz of its clock, the CPU
// 11.4 per 400 MHz of its own, and the line FIFO's tdp costs the FHG 5 %. The rate is the
// lesser; the budget is 10.
TEST(Doubt, PercentilesProbabilityAndSensitivityOfAKnownChip) {
    const auto u = three_unknowns();
    const JointDesign d = joint_design(u, 200, 1);
    std::vector<Json> results;
    std::vector<double> rates;
    for (const auto& sets : d.sets) {
        const double fhg = 9.6 * std::stod(sets[0].second) / 100 * (sets[2].second == "tdp" ? 0.95 : 1.0);
        const double cpu = 11.4 * std::stod(sets[1].second) / 400;
        rates.push_back(std::min(fhg, cpu));
        results.push_back({{"fps", rates.back()}, {"alone_fps", {{"fhg", fhg}, {"cpu", cpu}}}});
    }
    results[7] = {{"error", "refused"}, {"exit", 2}};
    const Json j = doubt_json(u, d, results, 9.5, 9.5, 10, 2);
    EXPECT_EQ(j["points"], 200);
    ASSERT_EQ(j["failed_points"].size(), 1u);
    EXPECT_EQ(j["failed_points"][0]["point"], 7);
    rates.erase(rates.begin() + 7);
    std::sort(rates.begin(), rates.end());
    EXPECT_NEAR(j["fps"]["p50"].get<double>(), rates[99], 1e-9);  // the middle of 199
    EXPECT_DOUBLE_EQ(j["fps"]["min"].get<double>(), rates.front());
    const double met =
        double(std::count_if(rates.begin(), rates.end(), [](double r) { return r >= 10; })) / double(rates.size());
    EXPECT_DOUBLE_EQ(j["probability_met"].get<double>(), met);
    EXPECT_GT(j["surrogate"]["r2"].get<double>(), 0.95);  // the chip is log-linear per resource
    std::map<std::string, std::pair<double, double>> s;
    for (const auto& row : j["sensitivity"]) s[row["parameter"]] = {row["first_order"], row["total"]};
    // The CPU (8.6 to 15.7 frames/s over its band) is the lesser only below ~350 MHz, a fifth of
    // its band: the FHG's clock matters most, the CPU's through that fifth, the FIFO least.
    EXPECT_GT(s["fhg.clock"].second, 0.5);
    EXPECT_GT(s["fhg.clock"].second, s["cpu.clock"].second);
    EXPECT_GT(s["cpu.clock"].second, s["fhg.line_fifo"].second);
    EXPECT_GT(s["cpu.clock"].second, 0.05);
    for (const auto& [key, v] : s) {
        EXPECT_GE(v.second + 0.05, v.first) << key << ": the total effect includes the first-order one";
        EXPECT_LE(v.second, 1.02) << key;
    }
}

}  // namespace
}  // namespace surfvp
