// The chip end to end on real frames: the VP against direct mode, pipelining, the budget
// verdict, and a hardware error in one task.
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using test::fresh_dir;
using test::slurp;
using test::surfvp;

const std::string kBudget = std::string(SURFVP_SOURCE_DIR) + "/scenarios/budget_1024x768.yaml";

nlohmann::json run(const std::string& name, const std::string& sets, int expected_exit) {
    const std::string out = fresh_dir(name);
    const auto r = surfvp("run " + kBudget + " --trace none --quiet --out " + out + " " + sets);
    EXPECT_EQ(r.exit_code, expected_exit) << r.err;
    return nlohmann::json::parse(slurp(out + "/report.json"));
}

TEST(SurfRun, VpKeypointsEqualDirectModeByteForByte) {
    const std::string vp = fresh_dir("vp"), direct = fresh_dir("direct");
    const std::string sets = " --set surf.frames=3 --set surf.width=512 --set surf.height=384 --set budget.fps=0";
    ASSERT_EQ(surfvp("run " + kBudget + " --trace none --quiet --out " + vp + sets).exit_code, 0);
    ASSERT_EQ(surfvp("run " + kBudget + " --direct --quiet --out " + direct + sets).exit_code, 0);
    size_t files = 0;
    for (const auto& entry : fs::directory_iterator(vp + "/keypoints")) {
        const std::string name = entry.path().filename().string();
        EXPECT_EQ(slurp(entry.path().string()), slurp(direct + "/keypoints/" + name)) << name;
        ++files;
    }
    EXPECT_EQ(files, 6u);  // 3 frames: .surf and .surf.meta
    EXPECT_GT(slurp(vp + "/keypoints/frame_0000.surf").size(), 1000u);
}

TEST(SurfRun, TwoTasksInFlightOverlapHardwareAndSoftware) {
    const std::string sets = " --set surf.frames=6 --set surf.width=512 --set surf.height=384 --set budget.fps=0";
    const auto one = run("one", sets + " --set surf.tasks_in_flight=1", 0);
    const auto two = run("two", sets + " --set surf.tasks_in_flight=2", 0);
    EXPECT_GT(two["throughput_fps"].get<double>(), one["throughput_fps"].get<double>());
    // Pipelined, the rate is the slowest resource's.
    double slowest_ms = 0;
    for (const auto& [name, ms] : two["busy_per_frame_ms"].items()) slowest_ms = std::max(slowest_ms, ms.get<double>());
    EXPECT_NEAR(two["throughput_fps"].get<double>(), 1000.0 / slowest_ms, 0.03 * 1000.0 / slowest_ms);
}

TEST(SurfRun, BudgetVerdictFollowsTheFhgClock) {
    const std::string sets = " --set surf.frames=4";
    const auto slow = run("slow", sets + " --set fhg.clock=90MHz", 1);
    EXPECT_FALSE(slow["budget"]["met"].get<bool>());
    EXPECT_EQ(slow["bottleneck"], "fhg");
    const auto fast = run("fast", sets + " --set fhg.clock=125MHz", 0);
    EXPECT_TRUE(fast["budget"]["met"].get<bool>());
    EXPECT_GT(fast["throughput_fps"].get<double>(), 10.0);
}

TEST(SurfRun, HardwareErrorFailsOnlyItsTask) {
    const auto r = run("fault", " --set surf.frames=4 --set surf.width=512 --set surf.height=384 --set budget.fps=0 --set fault.frame=2", 1);
    const auto& frames = r["workload"]["per_frame"];
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_NE(frames[1]["error"].get<std::string>().find("bus error"), std::string::npos) << frames[1];
    for (int i : {0, 2, 3}) {
        EXPECT_FALSE(frames[i].contains("error")) << frames[i];
        EXPECT_GT(frames[i]["keypoints"].get<int>(), 0);
    }
    EXPECT_EQ(r["frames_done"], 3);
}

}  // namespace
}  // namespace surfvp
