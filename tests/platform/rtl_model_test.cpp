// fhg.model=rtl: the platform with the verilated Verilog datapath (models/fhg/rtl) in place of
// HessianCore and the sequence's interval. On a 320 x 240 budget run it must give the model's
// keypoints and frame timing exactly: every file and every figure of the run but wall clock.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

#include "cli.h"
#include "same_figures.h"

namespace surfvp {
namespace {
using test::fresh_dir;
using test::kBudget;
using test::slurp;
using test::surfvp;

const std::string kSmallBudget =
    test::kOneRun + " --set surf.frames=4 --set surf.width=320 --set surf.height=240 --trace none --quiet";

TEST(FhgRtlModel, GivesTheModelsKeypointsAndFrameTimingOnA320x240BudgetRun) {
    REQUIRE_OPENCV_DATA("graf1.png");
    std::string outs[2];
    for (int rtl = 0; rtl < 2; ++rtl) {
        outs[rtl] = fresh_dir(rtl ? "fhg_rtl" : "fhg_core");
        const auto r =
            surfvp("run " + kBudget + kSmallBudget + " --out " + outs[rtl] + (rtl ? " --set fhg.model=rtl" : ""));
        ASSERT_LE(r.exit_code, 1) << r.err;
    }
    const nlohmann::json core = nlohmann::json::parse(slurp(outs[0] + "/report.json")),
                         rtl = nlohmann::json::parse(slurp(outs[1] + "/report.json"));
    test::expect_same_figures(core, rtl, "fhg.model=rtl");
    EXPECT_EQ(slurp(outs[0] + "/frames.csv"), slurp(outs[1] + "/frames.csv"));  // each frame's times
    size_t keypoints = 0;
    for (const auto& file : std::filesystem::directory_iterator(outs[0] + "/keypoints")) {
        const std::string name = file.path().filename().string();
        EXPECT_EQ(slurp(file.path().string()), slurp(outs[1] + "/keypoints/" + name)) << name;
        keypoints += file.file_size();
    }
    EXPECT_GT(keypoints, 4u * 50 * 64);  // four frames of real keypoints compared, not empty files
    EXPECT_NE(slurp(outs[1] + "/config.yaml").find("model: rtl"), std::string::npos);
}

// What the build did not verilate, and what the RTL does not time, is refused before anything
// runs, naming the parameter.
TEST(FhgRtlModel, AConfigurationTheBuildCannotRunIsBadInput) {
    const std::string out = test::fresh_path("fhg_rtl_refused");
    auto r = surfvp("run " + kBudget + kSmallBudget + " --out " + out +
                    " --set fhg.model=rtl --set 'fhg.response_bits=16 bit'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--set fhg.model: rtl runs the FHG datapath verilated for the defaults, but RESPONSE_BITS = "
                         "16 here, 18 in the build"),
              std::string::npos)
        << r.err;
    r = surfvp("run " + kBudget + kSmallBudget + " --out " + out +
               " --set fhg.model=rtl --set 'fhg.cycles_per_block=60 cycles'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("but fhg.cycles_per_block is 60 cycles (from --set); the RTL's is 0"), std::string::npos)
        << r.err;
    r = surfvp("run " + kBudget + kSmallBudget + " --out " + out +
               " --set fhg.model=rtl --set 'fhg.x3_cycles=2 cycles'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--set fhg.model: rtl cannot run this configuration: the RTL builds a x3 as one step or three "
                         "additions: fhg.x3_cycles must be 1 or 3"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace surfvp
