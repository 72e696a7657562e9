// The power estimate (docs/power.md): each block's watts from what the run did and the power.*
// prices, checked against the formula on a made-up second of activity, and the budget run
// against the paper's "less than 10 W".
#include <gtest/gtest.h>

#include "cli.h"
#include "platform/cost/power.h"
#include "platform/scenario/scenario.h"

namespace surfvp {
namespace {
using Json = nlohmann::ordered_json;

TEST(Power, EachBlockIsItsActivityTimesItsPrice) {
    const Config c = load_scenario(test::kBudget, {});
    const FpgaResources res = fpga_resources(c);
    // One second: the CPU computes half of it, the FHG a quarter, 1 GB each way on PLB2 in
    // 1000 bursts, 2 Gbit to and from DDR; the clocks as the statistics report them.
    const Json r = {
        {"sim_time_s", 1.0},
        {"frames_done", 4},
        {"cpu", {{"cycles_consumed", 200'000'000}, {"clock_hz", 400e6}}},
        {"fhg", {{"computing_s", 0.25}, {"clock_hz", 100e6}}},
        {"iig", {{"computing_s", 0.0}, {"clock_hz", 100e6}}},
        {"buses",
         {{"plb2", {{"read", {{"bytes", 0}, {"bursts", 0}}}, {"write", {{"bytes", 125'000'000}, {"bursts", 1000}}}}}}},
        {"memory", {{"bytes_read", 125'000'000}, {"bytes_written", 125'000'000}}}};
    const Json p = power_estimate(c, r, res);
    const auto& b = p["blocks"];
    EXPECT_DOUBLE_EQ(b["fpga static"]["watts"].get<double>(), 1.2);
    EXPECT_DOUBLE_EQ(b["ppc440"]["watts"].get<double>(), 0.5e-3 * 400 * 0.5);  // mW/MHz x MHz x busy share
    EXPECT_NEAR(b["buses"]["watts"].get<double>(), 1e9 * 2e-12 + 1000 * 50e-12, 1e-12);
    EXPECT_NEAR(b["ddr traffic"]["watts"].get<double>(), 2e9 * 60e-12, 1e-12);
    // The FHG: 25 M cycles of its logic, 4 buses x 2 lines of block-RAM reads a cycle, 18
    // determinants of 3 products per 60-cycle block.
    const double cycles = 0.25 * 100e6;
    const double fhg_cells = res.blocks[1].luts + res.blocks[1].ffs;
    EXPECT_NEAR(b["fhg"]["watts"].get<double>(),
                fhg_cells * 0.05e-12 * cycles + cycles * 8 * 20e-12 + cycles / 53 * 18 * 3 * 10e-12, 1e-9);
    double sum = 0;
    for (const auto& [name, block] : b.items()) sum += block["watts"].get<double>();
    EXPECT_NEAR(p["watts"].get<double>(), sum, 1e-12);
    EXPECT_NEAR(p["joules_per_frame"].get<double>(), sum / 4, 1e-12);
    EXPECT_TRUE(p["within_budget"].get<bool>());
}

TEST(Power, TheBudgetRunStaysWithinTenWattsAndAFasterFhgCostsMore) {
    auto watts = [](const std::string& name, const std::string& sets) {
        const std::string out = test::fresh_dir(name);
        const auto r = test::surfvp("run " + test::kBudget + " --quiet --trace none --out " + out + test::kOneRun +
                                    " --set surf.frames=3 --set budget.fps=0" + sets);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return nlohmann::json::parse(test::slurp(out + "/report.json"))["power"];
    };
    const auto base = watts("power_base", ""), fast = watts("power_fast", " --set fhg.clock=125MHz");
    EXPECT_GT(base["watts"].get<double>(), 2.0);
    EXPECT_LT(base["watts"].get<double>(), 10.0);  // the paper: less than 10 W
    EXPECT_TRUE(base["within_budget"].get<bool>());
    EXPECT_GT(fast["watts"].get<double>(), base["watts"].get<double>());
    EXPECT_LT(fast["joules_per_frame"].get<double>(),
              base["joules_per_frame"].get<double>());  // static power over fewer seconds
    EXPECT_NE(test::slurp(test::fresh_path("power_base") + "/report.md").find("## Power and energy"),
              std::string::npos);
    // The cost parameters' band, re-evaluated on the same run: static power 1.2 W -> 0.8 .. 2 W.
    const auto& band = base["band"];
    EXPECT_LT(band["watts_range"][0].get<double>(), base["watts"].get<double>());
    EXPECT_GT(band["watts_range"][1].get<double>(), base["watts"].get<double>());
    bool found = false;
    for (const auto& e : band["parameters"])
        if (e["parameter"] == "power.static_w") {
            found = true;
            EXPECT_NEAR(e["low"]["watts"].get<double>(), base["watts"].get<double>() - 0.4, 1e-9);
            EXPECT_NEAR(e["high"]["watts"].get<double>(), base["watts"].get<double>() + 0.8, 1e-9);
        } else if (e["parameter"] == "fpga.infrastructure_ramb36") {
            EXPECT_EQ(e["low"]["ramb36"], 83);  // 85 with 6: 4 .. 12
            EXPECT_EQ(e["high"]["ramb36"], 91);
        }
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace surfvp
