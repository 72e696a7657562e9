// Faults injected through the scenario (docs/faults.md): libSSA2 detects each, fails only the
// frame it strikes, resets the pair, and the other frames come out as in a run without faults.
// A fault that cannot strike is bad input.
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli.h"

namespace surfvp::test {
namespace {

const std::string kFaults = std::string(SURFVP_SOURCE_DIR) + "/scenarios/faults.yaml";

nlohmann::json run_faults(const std::string& name, const std::string& sets, int expected_exit) {
    const std::string out = fresh_dir(name);
    const auto r = surfvp("run " + kFaults + " --quiet --trace none --out " + out + sets);
    EXPECT_EQ(r.exit_code, expected_exit) << r.err;
    return nlohmann::json::parse(slurp(out + "/report.json"));
}

TEST(Faults, EveryKindAtOnceIsDetectedAndOnlyItsFrameIsLost) {
    const auto r = run_faults("all", "", 0);
    const auto& faults = r["faults"];
    EXPECT_EQ(faults["given"], 9);
    EXPECT_EQ(faults["injected"], 9);
    EXPECT_EQ(faults["detected"], 9);
    EXPECT_EQ(faults["recovered"], 9);
    EXPECT_EQ(faults["tasks_lost"], 7);  // the two lost interrupts cost time, not the frame
    EXPECT_EQ(r["frames_done"], 5);
    const auto& frames = r["workload"]["per_frame"];
    const std::vector<std::pair<int, std::string>> lost = {
        {1, "FHG determinant DMA write got a bus error"},
        {3, "IIG integral DMA write got a bus error"},
        {5, "the IIG's interrupt line is stuck: 64 interrupts in a row"},
        {6, "the maxima FIFO overflowed"},
        {7, "the FHG did not finish within the watchdog (100 ms)"},
        {8, "software check: candidate"},
        {10, "IIG integral DMA write got a bus error"}};  // its integral buffer outside memory
    for (const auto& [frame, why] : lost)
        EXPECT_NE(frames[frame].value("error", "").find(why), std::string::npos) << frames[frame];
    for (int frame : {4, 9}) {
        EXPECT_FALSE(frames[frame].contains("error")) << frames[frame];
        EXPECT_NE(frames[frame]["incidents"][0].get<std::string>().find("interrupt was lost"), std::string::npos);
    }
    EXPECT_EQ(r["faults"]["driver"]["watchdog_expiries"], 3);  // frames 4, 7 and 9
    EXPECT_EQ(r["faults"]["driver"]["spurious_interrupts"], 64);
}

// After every fault and reset, the frames that follow are bit-exact those of a clean run.
TEST(Faults, FramesAfterTheFaultsMatchARunWithout) {
    run_faults("with", "", 0);
    const std::string clean = fresh_dir("without");
    const auto r = surfvp("run " + kFaults + " --quiet --trace none --out " + clean + " --set 'faults=[]'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"frame_0000.surf", "frame_0004.surf", "frame_0009.surf", "frame_0011.surf"})
        EXPECT_EQ(slurp(fresh_path("with") + "/keypoints/" + f), slurp(clean + "/keypoints/" + f)) << f;
    EXPECT_FALSE(std::filesystem::exists(fresh_path("with") + "/keypoints/frame_0007.surf"));
}

// The run did not do what it was asked to: it broke (exit 6), not a design that missed a goal.
TEST(Faults, AFaultThatNeverStrikesFailsTheRun) {
    const auto r = run_faults("never", " --set 'faults=[{kind: bus_error, master: fhg, burst: 999999999}]'", 6);
    EXPECT_EQ(r["faults"]["given"], 1);  // in place of the scenario's
    EXPECT_EQ(r["faults"]["injected"], 0);
    bool named = false;
    for (const auto& c : r["checks"])
        if (c["name"] == "every injected fault detected") {
            EXPECT_FALSE(c["passed"].get<bool>());
            named = c["detail"].get<std::string>().find("bus_error on fhg's burst 999999999 never struck") !=
                    std::string::npos;
        }
    EXPECT_TRUE(named) << r["checks"];
}

TEST(Faults, AFaultThatCannotStrikeIsBadInput) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"[{kind: lost_interrupt, block: fhg, frame: 12}]", "past the last frame (surf.frames = 12: frames 0 to 11)"},
        {"[{kind: bus_error, master: fhg1, burst: 3}]", "no PLB2 master 'fhg1' drives this workload: iig or fhg"},
        {"[{kind: melt, frame: 1}]", "'melt' is not a fault kind"},
        {"[{kind: fifo_overflow, frame: 1, colour: red}]", "fifo_overflow takes kind, frame, block, not 'colour'"},
        {"[{kind: fifo_overflow, block: iig, frame: 1}]", "only the FHG has a maxima FIFO"},
        {"[{kind: never_finishes, frame: 1}]", "never_finishes needs block: iig or fhg"},
        {"[{kind: bus_error, master: iig, burst: 0}]", "burst counts from 1"},
        {"[{kind: stuck_interrupt, block: iig, frame: x}]", "'x' is not a whole number"},
    };
    for (const auto& [faults, message] : cases) {
        const auto r = surfvp("validate " + kFaults + " --set 'faults=" + faults + "'");
        EXPECT_EQ(r.exit_code, 2) << faults << ": " << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << faults << ": " << r.err;
    }
    const auto watchdog = surfvp("validate " + kFaults + " --set surf.watchdog=0s");
    EXPECT_EQ(watchdog.exit_code, 2);
    EXPECT_NE(watchdog.err.find(
                  "faults.yaml:17: faults: lost_interrupt on fhg, frame 4: only the driver's watchdog finds it"),
              std::string::npos)
        << watchdog.err;
    const auto smoke = surfvp("validate " + kFaults + " --set run.workload=smoke");
    EXPECT_NE(smoke.err.find("faults: need run.workload = surf"), std::string::npos) << smoke.err;
    const std::string out = fresh_path("direct");
    const auto direct = surfvp("run " + kFaults + " --direct --quiet --out " + out);
    EXPECT_EQ(direct.exit_code, 2);
    EXPECT_NE(direct.err.find("--direct has no time"), std::string::npos) << direct.err;
    EXPECT_FALSE(std::filesystem::exists(out));  // refused before anything was written
}

}  // namespace
}  // namespace surfvp::test
