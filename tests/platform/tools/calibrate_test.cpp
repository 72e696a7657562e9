// `surfvp calibrate` end to end on a small input: the VP records its stage's input, the
// PPC440 build runs it under qemu-ppc with the same keypoints, and the stream is fitted into
// a table that prices the same work as the recorded one (the per-unit instruction streams do
// not depend on the image size). Needs g++-powerpc-linux-gnu and qemu-user
// (scripts/bootstrap.sh installs both); fails, never skips, without them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "sw/cpu_cost/calibration.h"

namespace surfvp::test {
namespace {

// With --set on a pipeline knob the stream is timed there (the table's defaults are the set
// value), and the table it fits prices the work as the recorded table re-timed there does.
TEST(Calibrate, RunsTheStageUnderTheIssAndFitsItsPrices) {
    const std::string dir = fresh_dir("calibrate");
    const Cli r = surfvp(
        "calibrate --fit budget_1024x768 --check none --frames 1 --no-probes --set surf.width=256 "
        "--set surf.height=192 --set apu.load_issue=2cycles --set apu.outstanding_loads=2 --quiet --out " +
        dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("| descriptor |"), std::string::npos) << r.out;
    const auto report = nlohmann::json::parse(slurp(dir + "/calibration_report.json"));
    ASSERT_EQ(report["runs"].size(), 4u);  // exact and rounded Haar, each also with M-SURF (--msurf)
    const auto recorded =
        nlohmann::json::parse(slurp(std::string(SURFVP_SOURCE_DIR) + "/sw/cpu_cost/calibration.json"));
    for (const auto& run : report["runs"]) {
        const std::string haar = run["haar"];
        EXPECT_TRUE(run["results"]["agree"].get<bool>()) << run["results"].dump();
        EXPECT_GT(run["results"]["keypoints"].get<int>(), 20) << haar;
        EXPECT_GT(run["instructions_executed"].get<double>(), 1e6) << haar;
        EXPECT_TRUE(run["unclassified_mnemonics"].empty()) << run["unclassified_mnemonics"].dump();
        // Fitted on itself: the table prices its own stream to within a few percent.
        EXPECT_LT(std::abs(run["agreement"]["total_error"].get<double>()), 0.02) << haar;
        // Timed at the settings given, for both precisions.
        for (const char* precision : {"single", "double"}) {
            EXPECT_EQ(report["calibration"][precision]["defaults"]["apu.load_issue"].get<double>(), 2.0);
            EXPECT_EQ(report["calibration"][precision]["defaults"]["apu.outstanding_loads"].get<double>(), 2.0);
        }
        // A descriptor's stream on this small image, timed there, costs what the recorded
        // table's sample re-timed there says; and less than at the defaults (loads that no
        // longer hold the APU).
        sw::PipelineParams quick;
        quick.apu_load_issue = 2;
        quick.apu_outstanding_loads = 2;
        const surf::HaarMode mode = haar == "rounded" ? surf::HaarMode::rounded : surf::HaarMode::exact;
        const size_t d = size_t(sw::Unit::descriptor);
        const double fitted = report["calibration"]["single"]["haar"][haar]["descriptor"]["cycles"];
        EXPECT_NEAR(fitted / sw::unit_prices(mode, quick)[d], 1.0, 0.05) << haar;
        EXPECT_LT(fitted, 0.98 * recorded["single"]["haar"][haar]["descriptor"]["cycles"].get<double>()) << haar;
        // M-SURF priced as its own unit: 576 samples to Bay's 400, and its weights.
        const double msurf = report["calibration"]["single"]["haar"][haar]["msurf"]["cycles"];
        EXPECT_GT(msurf, 1.2 * fitted) << haar;
        EXPECT_LT(msurf, 2.5 * fitted) << haar;
    }
    EXPECT_TRUE(std::filesystem::exists(dir + "/calibration.md"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/calibration.json"));
}

TEST(Calibrate, RefusesWhatItCannotUse) {
    const Cli frames = surfvp("calibrate --frames 0 --out " + fresh_dir("calibrate_bad"));
    EXPECT_EQ(frames.exit_code, 2);
    EXPECT_NE(frames.err.find("--frames"), std::string::npos) << frames.err;
    const Cli firmware = surfvp("calibrate --firmware /nonexistent/stage_firmware --out " + fresh_dir("calibrate_bad"));
    EXPECT_EQ(firmware.exit_code, 2);
    EXPECT_NE(firmware.err.find("/nonexistent/stage_firmware"), std::string::npos) << firmware.err;
    EXPECT_NE(firmware.err.find("g++-powerpc-linux-gnu"), std::string::npos) << firmware.err;
    // Options that would fail only once the fit had run (a quarter of an hour) fail first, and
    // leave no output folder behind.
    const std::string out = fresh_path("calibrate_never");
    std::filesystem::remove_all(out);
    for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
             {"--check nope", "--check nope: nope: no such scenario file"},
             {"--fit graf --set surf.frames=x", "--fit graf: --set: surf.frames: 'x' is not a whole number"},
             {"--table /nonexistent/calibration.json", "--table /nonexistent/calibration.json: no folder /nonexistent"},
             {"--table " + fresh_dir("calibrate_table"), "is a folder, not a file to write"},
             {"--firmware " + fresh_dir("calibrate_firmware_folder"), "not a regular file (a PPC440 ELF is)"},
             {"--firmware " + std::string(SURFVP_SOURCE_DIR) + "/README.md", "README.md.map beside the firmware"}}) {
        const Cli r = surfvp("calibrate " + args + " --out " + out);
        EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
        EXPECT_NE(r.err.find(says), std::string::npos) << args << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << args;
    }
}

}  // namespace
}  // namespace surfvp::test
