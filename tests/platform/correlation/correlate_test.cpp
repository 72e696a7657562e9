// `surfvp correlate`: the region of the unknowns in which the VP reproduces the paper's figures,
// found by re-simulation; the shipped defaults lie inside it, a scenario at another frame size
// outside, and the schedules that reproduce the basic script's overhead are exactly the ones
// whose line FIFO serves four reads a line and cycle.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <set>

#include "cli.h"

namespace surfvp {
namespace {
using test::fresh_dir;
using test::slurp;
using test::surfvp;

std::set<std::string> reproducing_schedules(const nlohmann::json& r) {
    std::set<std::string> out;
    for (const auto& s : r["schedules"])
        if (s["reproduces"].get<bool>())
            out.insert(s["fhg.bus_word"].get<std::string>() + "/" + s["fhg.line_fifo"].get<std::string>() + "/" +
                       s["fhg.read_buses"].get<std::string>());
    return out;
}

TEST(Correlate, TheDefaultsLieInTheRegionThatReproducesThePaper) {
    const std::string out = fresh_dir("correlate_default");
    const auto run = surfvp("correlate --quiet --out " + out);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto r = nlohmann::json::parse(slurp(out + "/correlate.json"));
    // Each bus reaching half of the lines (fhg.line_groups = 2), only tdp_x2 keeps the crossbar's
    // 53 cycles; banked takes 54 (+12.5 %).
    EXPECT_EQ(reproducing_schedules(r), (std::set<std::string>{"quad/tdp_x2/4"}));
    EXPECT_TRUE(r["defaults"]["inside"].get<bool>()) << r["defaults"];
    EXPECT_EQ(r["failed_points"].size(), 0u) << r["failed_points"];
    // Each point's verdict is its rate against the paper's 9 to 11 frames/s.
    size_t inside = 0;
    for (const auto& p : r["points"]) {
        const double fps = p["fps"].get<double>();
        EXPECT_EQ(p["reproduces"].get<bool>(), fps >= 9.0 - 1e-9 && fps <= 11.0 + 1e-9) << p;
        inside += p["reproduces"].get<bool>();
    }
    EXPECT_GT(inside, 0u);
    EXPECT_LT(inside, r["points"].size());  // the region is a part of the bands, not all of them
    const std::string md = slurp(out + "/correlate.md");
    EXPECT_NE(md.find("Inside the region"), std::string::npos);
    EXPECT_EQ(slurp(out + "/correlate.svg").rfind("<svg", 0), 0u);
}

TEST(Correlate, AnotherFrameSizeIsOutsideAndSaysWhy) {
    const std::string out = fresh_dir("correlate_small");
    const auto run =
        surfvp("correlate budget_1024x768 --quiet --set surf.width=512 --set surf.height=384 --out " + out);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto r = nlohmann::json::parse(slurp(out + "/correlate.json"));
    EXPECT_FALSE(r["defaults"]["inside"].get<bool>());
    EXPECT_NE(r["defaults"]["why"].get<std::string>().find("is not about 10"), std::string::npos) << r["defaults"];
    EXPECT_EQ(surfvp("correlate smoke --quiet --out " + fresh_dir("correlate_smoke")).exit_code,
              2);  // not a SURF scenario
}

}  // namespace
}  // namespace surfvp
