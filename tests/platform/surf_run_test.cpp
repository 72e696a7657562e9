// The chip end to end on real frames: the VP against direct mode, pipelining, the budget
// verdict, and a hardware error in one task.
#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <tuple>

#include "cli.h"
#include "sw/eval/keypoint_file.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using test::fresh_dir;
using test::slurp;
using test::surfvp;

using test::kBudget;
using test::kOneRun;
const std::string kCastle = std::string(SURFVP_SOURCE_DIR) + "/scenarios/castle_sequence.yaml";
using test::fresh_path;

nlohmann::json run(const std::string& name, const std::string& sets, int expected_exit,
                   const std::string& scenario = kBudget) {
    const std::string out = fresh_dir(name);
    const auto r = surfvp("run " + scenario + " --trace none --quiet --out " + out + kOneRun + " " + sets);
    EXPECT_EQ(r.exit_code, expected_exit) << r.err;
    return nlohmann::json::parse(slurp(out + "/report.json"));
}

TEST(SurfRun, VpKeypointsEqualDirectModeByteForByte) {
    const std::string vp = fresh_dir("vp"), direct = fresh_dir("direct");
    const std::string sets = " --set surf.frames=3 --set surf.width=512 --set surf.height=384 --set budget.fps=0";
    ASSERT_EQ(surfvp("run " + kBudget + " --trace none --quiet --out " + vp + kOneRun + sets).exit_code, 0);
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

// The maxima FIFO is FhgRegisters in both: with 8 entries and a FIFO interrupt that never
// comes (its level is above the depth), the driver drains only at DONE, and both drop the
// same candidates.
TEST(SurfRun, VpAndDirectModeReportTheSameOverflowOnATinyFifo) {
    const std::string vp = fresh_dir("vp_overflow"), direct = fresh_dir("direct_overflow");
    const std::string sets =
        " --set surf.frames=1 --set surf.width=512 --set surf.height=384 --set budget.fps=0"
        " --set fhg.maxima_fifo_depth=8 --set surf.fifo_irq_level=1024";
    EXPECT_EQ(surfvp("run " + kBudget + " --trace none --quiet --out " + vp + kOneRun + sets).exit_code, 6);
    EXPECT_EQ(surfvp("run " + kBudget + " --direct --quiet --out " + direct + sets).exit_code, 6);
    const auto in_vp = nlohmann::json::parse(slurp(vp + "/report.json"));
    const auto in_direct = nlohmann::json::parse(slurp(direct + "/report.json"));
    const std::string why = in_vp["checks"][0]["detail"];
    EXPECT_EQ(why, in_direct["checks"][0]["detail"].get<std::string>());
    const uint64_t dropped = in_vp["fhg"]["candidates_dropped"];
    EXPECT_EQ(dropped + 8, in_vp["fhg"]["candidates"].get<uint64_t>());
    EXPECT_GT(dropped, 20u);
    EXPECT_EQ(why, fmt::format("frame 0: the maxima FIFO overflowed: {} candidates dropped", dropped));
}

TEST(SurfRun, TwoTasksInFlightOverlapHardwareAndSoftware) {
    const std::string sets = " --set surf.frames=6 --set surf.width=512 --set surf.height=384 --set budget.fps=0";
    const auto one = run("one", sets + " --set surf.tasks_in_flight=1", 0);
    const auto two = run("two", sets + " --set surf.tasks_in_flight=2", 0);
    EXPECT_GT(two["throughput_fps"].get<double>(), one["throughput_fps"].get<double>());
    // Pipelined, the rate is the busiest resource's.
    double busiest = 0;
    for (const auto& [name, row] : two["time_per_frame"].items())
        if (name != "accelerator pair") busiest = std::max(busiest, row["load"].get<double>());
    EXPECT_GT(busiest, 0.97) << two["time_per_frame"];
}

// The limit is named with its cause (docs/architecture.md#principles, 7), in four situations the report must
// tell apart.
TEST(SurfRun, LimitAtTheDefaultsIsTheBusyFhg) {
    const auto r = run("limit_default", " --set surf.frames=4 --set budget.fps=0", 0);
    EXPECT_EQ(r["limit"]["resource"], "fhg") << r["limit"];
    EXPECT_EQ(r["limit"]["cause"], "busy");
    EXPECT_GT(r["time_per_frame"]["fhg"]["load"].get<double>(), 0.99);
}

TEST(SurfRun, LimitWithAFiftyTwoLineFifoIsLineFifoStarvation) {
    const auto r = run("limit_fifo", " --set surf.frames=4 --set budget.fps=0 --set fhg.fifo_lines=52", 0);
    EXPECT_EQ(r["limit"]["resource"], "line fifo") << r["limit"];
    EXPECT_NE(r["limit"]["reason"].get<std::string>().find("starvation"), std::string::npos);
    const auto& fhg = r["time_per_frame"]["fhg"];
    EXPECT_GT(fhg["waits_ms"]["line FIFO empty"].get<double>(), 5.0);  // two lines' wait per block row
    EXPECT_LT(fhg["load"].get<double>(), 0.95);                        // the FHG alone is not the reason
}

TEST(SurfRun, LimitWithTwoPairsAndTwoTasksIsTheTaskLimit) {
    const auto r = run("limit_tasks",
                       " --set surf.frames=6 --set budget.fps=0 --set soc.accelerators=2 --set surf.tasks_in_flight=2" +
                           test::kRoomForTwoPairs,
                       0);
    // Each pair waits for a free task slot; the limit named is that wait (or, since the CPU's
    // fills overlap (issue 33), the IIG held back behind it on the PixelBus), not a busy block.
    EXPECT_TRUE(r["limit"]["resource"] == "task slots" || r["limit"]["cause"] == "PixelBus back-pressure")
        << r["limit"];
    EXPECT_GT(r["time_per_frame"]["accelerator pair"]["waits_ms"]["free task slot"].get<double>(), 10.0);
    EXPECT_LT(r["time_per_frame"]["cpu"]["load"].get<double>(), 0.95);  // not the CPU: it still waits for interrupts
}

// Every resource's frame adds up: busy + each wait + idle = its period, with no negative idle
// (the whole run's time per frame), at the defaults, under bus contention and with two pairs.
TEST(SurfRun, EveryResourcesFrameAddsUpToItsPeriod) {
    const std::string contention =
        " --set soc.accelerators=2 --set surf.tasks_in_flight=3 --set 'plb2.width=32 bit'"
        " --set 'memory.clock=100 MHz' --set 'memory.width=32 bit'";
    for (const auto& [name, sets] : std::vector<std::pair<std::string, std::string>>{
             {"adds_default", ""},
             {"adds_contention", contention},
             {"adds_two_pairs", " --set soc.accelerators=2 --set surf.tasks_in_flight=2"}}) {
        const auto r = run(name, " --set surf.frames=5 --set budget.fps=0" + test::kRoomForTwoPairs + sets, 0);
        const double run_period = r["sim_time_s"].get<double>() * 1e3 / r["frames_done"].get<double>();
        const double pairs = r["iig"].is_array() ? double(r["iig"].size()) : 1.0;
        ASSERT_TRUE(r.contains("time_per_frame")) << name;
        for (const auto& [resource, row] : r["time_per_frame"].items()) {
            double sum = row["busy_ms"].get<double>() + row["idle_ms"].get<double>();
            for (const auto& [cause, ms] : row["waits_ms"].items()) sum += ms.get<double>();
            const bool per_pair = resource == "iig" || resource == "fhg" || resource == "accelerator pair";
            EXPECT_NEAR(row["period_ms"].get<double>(), run_period * (per_pair ? pairs : 1.0), 1e-9)
                << name << " " << resource;
            EXPECT_NEAR(sum, row["period_ms"].get<double>(), 1e-6) << name << " " << resource << ": " << row;
            EXPECT_GE(row["idle_ms"].get<double>(), 0.0) << name << " " << resource;
            EXPECT_NEAR(row["busy_share"].get<double>(), row["busy_ms"].get<double>() / row["period_ms"].get<double>(),
                        1e-12);
        }
    }
}

TEST(SurfRun, LimitWithASlowIigIsTheIig) {
    // A slow IIG: the FHG waits for its lines, and that waiting is not the FHG's own time.
    const auto r = run("slow_iig", " --set surf.frames=3 --set iig.clock=5MHz --set budget.fps=0", 0);
    EXPECT_EQ(r["limit"]["resource"], "iig") << r["limit"];
    EXPECT_NEAR(r["time_per_frame"]["iig"]["busy_ms"].get<double>(), 1024.0 * 768 / 5e6 * 1e3, 0.5);  // 1 px a cycle
    EXPECT_GT(r["time_per_frame"]["fhg"]["waits_ms"]["line FIFO empty"].get<double>(), 30.0);
}

// A chip that could not have been built misses its goal, whatever its frame rate: every bus
// lane reaching every line (the crossbar) needs more LUTs than the FX70T places and routes, a
// 250 MHz FHG clocks the tdp_x2 line FIFO's block RAM at 500 MHz. The reason is the
// terminal's last line and report.md's first.
TEST(SurfRun, AChipThatCouldNotBeBuiltMissesItsGoal) {
    for (const auto& [name, sets, reason] :
         {std::tuple{"over_the_device", " --set fhg.line_groups=1",
                     "Not buildable: does not fit the XC5VFX70T: LUT: 43742 of 44800 (98 %), above the 85 % that "
                     "places and routes (fpga.max_utilisation)."},
          std::tuple{"over_the_bram_clock", " --set 'fhg.clock=250 MHz'",
                     "Not buildable: does not close: FHG line FIFO block RAM: 500 MHz, above its 450 MHz (2 x "
                     "fhg.clock (tdp_x2) against fpga.bram_fmax)."}}) {
        const std::string out = fresh_dir(name);
        const auto r = surfvp("run " + kBudget + " --trace none --out " + out + kOneRun + sets);
        EXPECT_EQ(r.exit_code, 1) << name << ": " << r.err;
        const std::string last = r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
        EXPECT_NE(last.find(std::string("FAILED: ") + reason), std::string::npos) << name << ": " << last;
        const std::string md = slurp(out + "/report.md");
        const size_t first = md.find("\n\n**"), result = md.find("**Result: FAILED**");
        EXPECT_EQ(md.find(reason), first + 4) << name << ": the reason comes first in report.md";
        EXPECT_LT(first, result) << name;
        const auto report = nlohmann::json::parse(slurp(out + "/report.json"));
        EXPECT_FALSE(report["passed"].get<bool>()) << name;
        EXPECT_FALSE(report["broken"].get<bool>()) << name;
    }
}

// With few keypoints the CPU keeps up and the FHG sets the rate.
TEST(SurfRun, BudgetVerdictFollowsTheFhgClock) {
    const std::string sets = " --set surf.frames=4 --set surf.target_keypoints=20";
    const auto slow = run("slow", sets + " --set fhg.clock=90MHz", 1);
    EXPECT_FALSE(slow["budget"]["met"].get<bool>());
    EXPECT_EQ(slow["bottleneck"], "fhg");
    const auto fast = run("fast", sets + " --set fhg.clock=125MHz", 0);
    EXPECT_TRUE(fast["budget"]["met"].get<bool>());
    EXPECT_GT(fast["throughput_fps"].get<double>(), 10.0);
}

TEST(SurfRun, HardwareErrorFailsOnlyItsTask) {
    // Castle frames differ from each other, so a frame described from another's buffers shows.
    const std::string sets = " --set surf.frames=4";
    const auto r =
        run("fault", sets + " --set 'faults=[{kind: dma_outside_memory, block: fhg, frame: 1}]'", 0, kCastle);
    run("no_fault", sets, 0, kCastle);
    // The other frames' keypoints are those of a run without the fault: the failed task did not
    // let a later one overwrite buffers the CPU was still reading.
    for (const char* f : {"frame_0000.surf", "frame_0002.surf", "frame_0003.surf"})
        EXPECT_EQ(slurp(fresh_path("fault") + "/keypoints/" + f), slurp(fresh_path("no_fault") + "/keypoints/" + f))
            << f;
    EXPECT_FALSE(
        std::filesystem::exists(fresh_path("fault") + "/keypoints/frame_0001.surf"));  // a failed frame has none
    const auto& frames = r["workload"]["per_frame"];
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_NE(frames[1]["error"].get<std::string>().find("bus error"), std::string::npos) << frames[1];
    for (int i : {0, 2, 3}) {
        EXPECT_FALSE(frames[i].contains("error")) << frames[i];
        EXPECT_GT(frames[i]["keypoints"].get<int>(), 0);
    }
    EXPECT_EQ(r["frames_done"], 3);
}

// Frames arrive in their task's buffer set as the task starts: memory holds two sets whatever
// the frame count (8 Castle frames of 640x480 once needed 2.3 MiB more than this), each reused
// frame buffer holds the right frame, and the VP, direct mode and a roomy memory agree.
TEST(SurfRun, FramesArriveInReusedBuffers) {
    const std::string sets = " --set surf.frames=8";
    const auto tight = run("tight", sets + " --set 'memory.size=15080 KiB'", 0, kCastle);
    const auto roomy = run("roomy", sets, 0, kCastle);
    const std::string direct = fresh_dir("streamed_direct");
    ASSERT_EQ(surfvp("run " + kCastle + " --direct --quiet --out " + direct + sets).exit_code, 0);
    EXPECT_EQ(surfvp("validate " + kCastle + sets + " --set 'memory.size=15079 KiB'").exit_code, 2);
    for (int i = 0; i < 8; ++i) {
        const std::string f = fmt::format("/keypoints/frame_{:04}.surf", i);
        const std::string kept = slurp(fresh_path("tight") + f);
        EXPECT_GT(kept.size(), 1000u) << f;
        EXPECT_EQ(kept, slurp(fresh_path("roomy") + f)) << f;
        EXPECT_EQ(kept, slurp(direct + f)) << f;
        if (i > 0) {
            EXPECT_NE(kept, slurp(fresh_path("tight") + fmt::format("/keypoints/frame_{:04}.surf", i - 1))) << f;
        }
    }
    EXPECT_EQ(tight["workload"]["evaluation"], roomy["workload"]["evaluation"]);
    EXPECT_GT(tight["workload"]["evaluation"]["distinguishability_gap1"]["pairs"].get<int>(), 0);
}

}  // namespace
}  // namespace surfvp

namespace surfvp {
namespace {

// The chip's keypoints against the float reference SURF (2 octaves, step 1, the same
// threshold) on the same 1024x768 frame: a reference keypoint is found when a chip keypoint
// lies within 1.5 px with a scale within 10 %.
TEST(SurfRun, ChipKeypointsMatchTheFloatReference) {
    const std::string out = fresh_dir("reference");
    const auto r = run("chip", " --set surf.frames=1 --set budget.fps=0 --set surf.target_keypoints=300", 0);
    // (direct mode gives the VP's keypoints byte for byte: VpKeypointsEqualDirectModeByteForByte)
    const double threshold = r["threshold"];
    const std::string chip_dir = fresh_dir("chip_keypoints");
    ASSERT_EQ(surfvp("run " + kBudget + " --direct --quiet --out " + chip_dir +
                     " --set surf.frames=1 --set budget.fps=0 --set surf.target_keypoints=300")
                  .exit_code,
              0);
    // The frame as the chip saw it: graf1 resized to 1024x768 (INTER_AREA), written as PNG.
    cv::Mat frame = cv::imread(std::string(OPENCV_DATA_DIR) + "/graf1.png", cv::IMREAD_GRAYSCALE), resized;
    ASSERT_FALSE(frame.empty()) << "install the Debian package opencv-doc";
    cv::resize(frame, resized, cv::Size(1024, 768), 0, 0, cv::INTER_AREA);
    cv::imwrite(out + "/frame.png", resized);
    ASSERT_EQ(
        surfvp(fmt::format(
                   "surf {}/frame.png --out {}/reference.surf --threshold {:.9g} --paper --octaves 2 --init-step 1 -q",
                   out, out, threshold))
            .exit_code,
        0);
    const auto reference = eval::load_keypoints(out + "/reference.surf");
    const auto chip = eval::load_keypoints(chip_dir + "/keypoints/frame_0000.surf");
    ASSERT_GT(reference.size(), 200u);
    size_t found = 0;
    for (const auto& k : reference)
        for (const auto& c : chip)
            if (std::hypot(k.x - c.x, k.y - c.y) <= 1.5f && std::abs(c.scale / k.scale - 1) <= 0.1f) {
                ++found;
                break;
            }
    const double fraction = double(found) / double(reference.size());
    std::printf("chip %zu keypoints, reference %zu: %.1f %% of the reference found\n", chip.size(), reference.size(),
                100 * fraction);
    EXPECT_GE(fraction, 0.9);
}

}  // namespace
}  // namespace surfvp

namespace surfvp {
namespace {

// The CPU's memory over PLB1 instead of the MCI: its fills and write-backs show on PLB1, and
// the FHG-bound frame rate hardly moves.
TEST(SurfRun, CpuMemoryOverPlb1) {
    const std::string sets = " --set surf.frames=3 --set budget.fps=0";
    const auto mci = run("mem_mci", sets, 0);
    const auto plb1 = run("mem_plb1", sets + " --set cpu.memory_path=plb1", 0);
    EXPECT_EQ(plb1["cpu"]["memory"]["path"], "plb1");
    EXPECT_EQ(plb1["buses"]["plb1"]["masters"]["cpu memory"]["bytes_read"], mci["cpu"]["memory"]["bytes_read"]);
    EXPECT_FALSE(plb1.contains("mci"));  // no MCI link on the chip, so no statistics of one
    EXPECT_NEAR(plb1["throughput_fps"].get<double>(), mci["throughput_fps"].get<double>(),
                0.01 * mci["throughput_fps"].get<double>());
    EXPECT_GT(plb1["cpu"]["memory"]["fill_stall_s"].get<double>(), mci["cpu"]["memory"]["fill_stall_s"].get<double>());
}

TEST(SurfRun, TooFewFramesForTheRateAreBadInput) {
    const auto r = surfvp("run " + kBudget + " --trace none --quiet --out " + fresh_dir("few") + kOneRun +
                          " --set surf.frames=2 --set soc.accelerators=2");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("surf.frames"), std::string::npos) << r.err;
}

// fhg.det_bits changes the determinant record in memory: 16-bit words halve what the FHG
// writes over PLB2 and into DDR, and the CPU reads them back from half the bytes.
TEST(SurfRun, DeterminantWidthSetsTheTrafficItCauses) {
    const std::string sets = " --set surf.frames=2 --set budget.fps=0 --set surf.target_keypoints=50";
    const auto wide = run("det32", sets, 0);
    const auto narrow = run("det16", sets + " --set 'fhg.det_bits=16 bit' --set 'fhg.det_frac_bits=4 bit'", 0);
    const uint64_t blocks = 512 * 384;
    EXPECT_EQ(wide["buses"]["plb2"]["masters"]["fhg"]["bytes_written"].get<uint64_t>(), 2 * blocks * 18 * 4);
    EXPECT_EQ(narrow["buses"]["plb2"]["masters"]["fhg"]["bytes_written"].get<uint64_t>(), 2 * blocks * 18 * 2);
    EXPECT_LT(narrow["buses"]["plb2"]["write"]["busy_s"].get<double>(),
              0.6 * wide["buses"]["plb2"]["write"]["busy_s"].get<double>());
    EXPECT_LT(narrow["cpu"]["memory"]["line_fills"].get<uint64_t>(),
              wide["cpu"]["memory"]["line_fills"].get<uint64_t>());
}

}  // namespace
}  // namespace surfvp

namespace surfvp::test {
namespace {

// The per-frame list goes to frames.csv (a header, a row per frame), the report renders the
// software stage as tables (no JSON in a cell) and names numbered files by their pattern.
TEST(SurfRunReport, FramesCsvAndAReadableWorkloadSection) {
    const std::string out = fresh_dir("readable");
    const auto r = surfvp("run " + kBudget + " --trace none --quiet --out " + out + kOneRun +
                          " --set surf.frames=3 --set surf.width=512 --set surf.height=384 --set budget.fps=0");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = slurp(out + "/frames.csv");
    EXPECT_EQ(csv.rfind("frame,candidates,keypoints,", 0), 0u) << csv;
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);  // the header and 3 frames
    const std::string md = slurp(out + "/report.md");
    EXPECT_EQ(md.find("{\""), std::string::npos) << md;  // no JSON in any cell
    // The rate first, then the blocks, the buses and DDR, the workload, every statistic.
    size_t at = md.find(" frames/s; limited by ");  // "**N frames/s; limited by X.**" heads the report
    ASSERT_NE(at, std::string::npos) << md;
    for (const char* section :
         {"## Frames", "## SSA FHG", "## SSA IIG", "## CPU (PPC440)", "### Software stage", "| descriptor |",
          "## Buses and DDR", "### DDR", "## Workload", "## Every statistic", "| `fhg.maxima_fifo_high_water` |"}) {
        const size_t next = md.find(section, at);
        EXPECT_NE(next, std::string::npos) << section << " missing or out of order";
        if (next != std::string::npos) at = next;
    }
    EXPECT_NE(md.find("`keypoints/frame_NNNN.surf` (3 files)"), std::string::npos);
    EXPECT_NE(md.find("`frames.csv`"), std::string::npos);
    const auto report = nlohmann::json::parse(slurp(out + "/report.json"));
    EXPECT_NE(std::find(report["outputs"].begin(), report["outputs"].end(), "frames.csv"), report["outputs"].end());
}

}  // namespace
}  // namespace surfvp::test
