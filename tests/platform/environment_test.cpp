// Inputs a hostile user gives and machines that refuse writes: each ends with a message that
// names the thing and its documented exit code (README: 2 bad input, 4 a refused write), and
// no file is left under a final name half written.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <elf.h>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <random>
#include <tuple>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"

namespace surfvp::test {
namespace {
namespace fs = std::filesystem;

const std::string kShort =
    kOneRun + " --set surf.frames=3 --set surf.width=512 --set surf.height=384 --set budget.fps=0";

TEST(Environment, ValuesThatDoNotFitOrAreNotNumbersAreBadInput) {
    for (const char* set : {"'fhg.recip_shift=4294967306 bit'", "'fhg.x3_cycles=1e30 cycles'", "budget.fps=nan",
                            "budget.fps=inf", "memory.efficiency=-nan"}) {
        const auto r = surfvp("validate " + kBudget + " --set " + set);
        EXPECT_EQ(r.exit_code, 2) << set << ": " << r.err;
        EXPECT_NE(r.err.find("surfvp: error:"), std::string::npos) << set << ": " << r.err;
    }
}

// A file-size limit stands in for a full disk: every write past it fails (EFBIG), as on a
// full disk (ENOSPC), without privileges.
int run_with_file_limit(const std::string& args, unsigned kib, std::string& err) {
    const std::string log = fresh_path("limited.err");
    const std::string command = "bash -c \"trap '' XFSZ; ulimit -f " + std::to_string(kib) + "; exec " +
                                std::string(SURFVP_BINARY) + " " + args + "\" 2>" + log;
    const int status = std::system(command.c_str());
    err = slurp(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Environment, AFullDiskWhileTracingEndsWithItsOwnExitCodeAndNoPartialFile) {
    for (const char* trace : {"perfetto", "vcd"}) {
        const std::string out = fresh_dir(std::string("full_") + trace);
        std::string err;
        EXPECT_EQ(
            run_with_file_limit("run " + kBudget + " --quiet --trace " + trace + " --out " + out + kShort, 64, err), 4)
            << err;
        EXPECT_NE(err.find("surfvp: cannot write: " + out + "/trace."), std::string::npos) << err;
        for (const auto& f : fs::directory_iterator(out))
            EXPECT_EQ(f.path().filename().string().find("trace."), std::string::npos) << f.path();
    }
}

// The keypoint files are written on the second thread (run.parallel) while the run goes on; a
// write that fails there still ends the run with the exit code of a full disk, naming the
// file, in the VP and in direct mode, and no keypoint file is left in the folder.
TEST(Environment, AFullDiskWhileWritingKeypointsEndsWithItsOwnExitCode) {
    for (const char* mode : {" --trace none", " --direct"}) {
        const std::string out = fresh_dir(std::string("full_keypoints") + (mode[3] == 'd' ? "_direct" : ""));
        std::string err;
        EXPECT_EQ(run_with_file_limit("run " + kBudget + " --quiet --out " + out + kShort + mode, 8, err), 4)
            << mode << err;
        EXPECT_NE(err.find("surfvp: cannot write: " + out + "/keypoints/frame_0000.surf"), std::string::npos)
            << mode << err;
        EXPECT_FALSE(fs::exists(out + "/keypoints")) << mode;
    }
}

// Two runs on one folder at once: the later one is refused while the first holds the folder,
// and what is left is the first one's complete output.
TEST(Environment, TwoRunsOnOneFolderDoNotCorruptEachOther) {
    const std::string out = fresh_dir("twice");
    // Long enough (40 frames) that it is still running when killed.
    std::string long_run = kShort;
    long_run.replace(long_run.find("surf.frames=3"), 13, "surf.frames=40");
    const std::string run =
        std::string(SURFVP_BINARY) + " run " + kBudget + " --quiet --trace all --out " + out + long_run;
    const std::string codes = fresh_path("twice.codes"), errors = fresh_path("twice.err");
    const int status = std::system(("(" + run + "; echo $? >>" + codes + ") 2>>" + errors + " & (" + run +
                                    "; echo $? >>" + codes + ") 2>>" + errors + "; wait")
                                       .c_str());
    ASSERT_TRUE(WIFEXITED(status));
    std::string sorted = slurp(codes);
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, "\n\n04") << slurp(errors);
    EXPECT_NE(slurp(errors).find("surfvp: cannot write: --out " + out + ": another surfvp run (pid "),
              std::string::npos)
        << slurp(errors);
    EXPECT_NO_THROW(nlohmann::json::parse(slurp(out + "/trace.perfetto.json")));
    EXPECT_NO_THROW(nlohmann::json::parse(slurp(out + "/report.json")));
    for (const auto& f : fs::directory_iterator(out))
        EXPECT_EQ(f.path().string().find("partial"), std::string::npos) << f.path();
    const std::string vcd = slurp(out + "/trace.vcd");
    EXPECT_EQ(vcd.rfind('#') != std::string::npos && vcd.back() == '\n', true);
}

// A folder used again holds only the last run's files: keypoints of frames it did not have
// and traces it did not ask for are gone; files surfvp did not write stay.
TEST(Environment, AReusedFolderHoldsOnlyTheLastRunsFiles) {
    const std::string out = fresh_dir("reused");
    write_file(out, "notes.txt", "mine");
    ASSERT_EQ(surfvp("run " + kBudget + " --quiet --trace all --out " + out + kShort).exit_code, 0);
    ASSERT_TRUE(fs::exists(out + "/keypoints/frame_0002.surf"));
    std::string two_frames = kShort;
    two_frames.replace(two_frames.find("surf.frames=3"), 13, "surf.frames=2");
    ASSERT_EQ(surfvp("run " + kBudget + " --quiet --trace none --out " + out + two_frames).exit_code, 0);
    EXPECT_TRUE(fs::exists(out + "/keypoints/frame_0001.surf"));
    for (const char* gone : {"keypoints/frame_0002.surf", "keypoints/frame_0002.surf.meta", "trace.vcd",
                             "trace.perfetto.json", "trace.gtkw"})
        EXPECT_FALSE(fs::exists(out + "/" + gone)) << gone;
    EXPECT_EQ(slurp(out + "/notes.txt"), "mine");
    EXPECT_EQ(nlohmann::json::parse(slurp(out + "/report.json"))["frames"], 2);
}

// A run that cannot write, or is killed, leaves the earlier output as it was; the next run
// clears what the killed one left.
TEST(Environment, AFailedOrKilledRunLeavesTheEarlierOutputIntact) {
    const std::string out = fresh_dir("intact");
    ASSERT_EQ(surfvp("run " + kBudget + " --quiet --trace none --out " + out + kShort).exit_code, 0);
    const std::string before = slurp(out + "/report.json");
    std::string err;
    EXPECT_EQ(run_with_file_limit("run " + kBudget + " --quiet --trace all --out " + out + kShort, 64, err), 4) << err;
    EXPECT_NE(err.find("what was in " + out + " before this run is as it was"), std::string::npos) << err;
    EXPECT_EQ(slurp(out + "/report.json"), before);

    // Long enough (40 frames) that it is still running when killed.
    std::string long_run = kShort;
    long_run.replace(long_run.find("surf.frames=3"), 13, "surf.frames=40");
    const std::string run =
        std::string(SURFVP_BINARY) + " run " + kBudget + " --quiet --trace all --out " + out + long_run;
    // Killed once its run folder exists beside the published one.
    std::system(("(" + run + " 2>/dev/null & pid=$!; while [ $(ls " + out +
                 "/.surfvp-runs | wc -l) -lt 2 ]; do sleep 0.05; done;"
                 " sleep 0.3; kill -9 $pid; wait $pid) 2>/dev/null")
                    .c_str());
    EXPECT_EQ(slurp(out + "/report.json"), before);
    const auto next = surfvp("run " + kBudget + " --quiet --trace none --out " + out + kShort);
    ASSERT_EQ(next.exit_code, 0);
    EXPECT_NE(next.err.find("took over the stale lock of a run that did not finish (pid "), std::string::npos)
        << next.err;
    EXPECT_EQ(std::distance(fs::directory_iterator(out + "/.surfvp-runs"), fs::directory_iterator()), 1);
    // A run that finished leaves nothing stale: the one after it says nothing.
    EXPECT_EQ(surfvp("run " + kBudget + " --quiet --trace none --out " + out + kShort).err, "");
}

size_t surf_files(const std::string& dir) {
    size_t n = 0;
    if (fs::is_directory(dir))
        for (const auto& f : fs::directory_iterator(dir)) n += f.path().extension() == ".surf";
    return n;
}

// What a user sees in `out` is one run's whole set: a run of N frames has N keypoint files,
// and traces exactly when it is the kind that writes them (N = 2); every name resolves, but
// when a kill landed in the moment around the switch (`dangling_allowed`): then a name only
// the other run wrote may be surfvp's link to nothing (reads as no file).
::testing::AssertionResult one_runs_set(const std::string& out, bool dangling_allowed = false) {
    if (!fs::exists(out + "/report.json")) return ::testing::AssertionSuccess() << "nothing published yet";
    const auto frames = nlohmann::json::parse(slurp(out + "/report.json"))["frames"].get<int>();
    if (surf_files(out + "/keypoints") != size_t(frames))
        return ::testing::AssertionFailure()
               << surf_files(out + "/keypoints") << " keypoint files beside a report of " << frames;
    if (fs::exists(out + "/trace.vcd") != (frames == 2))
        return ::testing::AssertionFailure()
               << "traces " << (frames == 2 ? "missing from" : "beside") << " a run of " << frames;
    for (const auto& e : fs::directory_iterator(out))
        if (e.path().filename().string()[0] != '.' && !fs::exists(e.path()) &&
            !(dangling_allowed && fs::is_symlink(e.path()) &&
              fs::read_symlink(e.path()) == fs::path(".surfvp-current") / e.path().filename()))
            return ::testing::AssertionFailure() << e.path() << " resolves to nothing";
    return ::testing::AssertionSuccess();
}

// Kills land at random instants spread over whole runs, their publishing included. Whatever the
// instant, the folder holds one run's set: the run before the kill or the killed one, whole.
TEST(Environment, AKillAtAnyInstantLeavesOneRunsWholeSet) {
    const std::string out = fresh_dir("killed_at_random");
    const std::string settings =
        kOneRun + " --set surf.width=256 --set surf.height=192 --set budget.fps=0 --quiet --out " + out;
    const auto command = [&](int frames) {
        return std::string(SURFVP_BINARY) + " run " + kBudget + settings +
               " --set surf.frames=" + std::to_string(frames) + (frames == 2 ? " --trace all" : " --trace none");
    };
    const auto start = std::chrono::steady_clock::now();
    ASSERT_EQ(std::system(command(1).c_str()), 0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::mt19937 random(34);
    std::uniform_real_distribution<double> instant(0.2 * seconds, 1.2 * seconds);
    int changed = 0, kept = 0;
    for (int kill = 0; kill < 40; ++kill) {
        const std::string before = slurp(out + "/report.json");
        std::system(("(" + command(1 + kill % 2) + " 2>/dev/null & pid=$!; sleep " + std::to_string(instant(random)) +
                     "; kill -9 $pid; wait $pid) 2>/dev/null")
                        .c_str());
        ASSERT_TRUE(one_runs_set(out, true)) << "kill " << kill;
        (slurp(out + "/report.json") == before ? kept : changed)++;
    }
    std::printf("40 kills over runs of %.3f s: %d left the earlier set, %d the killed run's\n", seconds, kept, changed);
    // As a kill around the switch leaves it: a link of surfvp's to a name no run wrote.
    fs::create_symlink(fs::path(".surfvp-current") / "trace.old", out + "/trace.old");
    ASSERT_EQ(std::system(command(2).c_str()), 0);  // and the next run cleans up after them
    EXPECT_FALSE(fs::is_symlink(out + "/trace.old"));
    EXPECT_TRUE(one_runs_set(out));
    EXPECT_EQ(std::distance(fs::directory_iterator(out + "/.surfvp-runs"), fs::directory_iterator()), 1);
}

// A shared folder where another user's run was killed: its lock file cannot be written by
// this user, yet no process holds it, so it is taken over with a warning, whether the folder
// lets this user replace the file (plain) or not (sticky, as /tmp).
TEST(Environment, AnotherUsersStaleLockIsTakenOverWithAWarning) {
    if (::geteuid() != 0) GTEST_SKIP() << "acting as another user needs root";
    const std::string shared = fresh_dir("shared");
    fs::permissions(shared, fs::perms::all);
    // The other user may not reach the build (a clone under /root): the binary and the scenario
    // are copied where it can.
    const std::string binary = shared + "/surfvp", scenario = shared + "/smoke.yaml";
    fs::copy_file(SURFVP_BINARY, binary);
    fs::copy_file(std::string(SURFVP_SOURCE_DIR) + "/scenarios/smoke.yaml", scenario);
    fs::permissions(binary, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                fs::perms::others_read | fs::perms::others_exec);
    fs::permissions(scenario,
                    fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
    for (const char* kind : {"plain", "sticky"}) {
        const std::string out = shared + "/" + kind;
        fs::create_directory(out);
        fs::permissions(out, fs::perms::all | (kind[0] == 's' ? fs::perms::sticky_bit : fs::perms::none));
        write_file(out, ".surfvp.lock", "999999\n");  // root's, 0644, no process holds it
        const std::string err = fresh_path(std::string(kind) + ".err");
        const int status = std::system(("SURFVP_CACHE=off setpriv --reuid=65534 --regid=65534 --clear-groups " +
                                        binary + " run " + scenario + " -q --out " + out + " 2>" + err)
                                           .c_str());
        EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0) << kind << ": " << slurp(err);
        EXPECT_NE(slurp(err).find("took over the stale lock of another user's run (pid 999999, no longer running)"),
                  std::string::npos)
            << kind << ": " << slurp(err);
        EXPECT_TRUE(fs::exists(out + "/report.json")) << kind;
    }
}

// An address-space limit stands in for a machine out of memory: the run ends with its own code
// (5), naming what it could not have, neither blaming the scenario (2) nor calling it a bug (3).
TEST(Environment, OutOfMemoryIsItsOwnOutcomeNamingTheAllocation) {
    const std::vector<std::tuple<std::string, unsigned, std::string>> cases = {
        {"run smoke --quiet", 150000,
         "surfvp: out of memory: the modelled DDR memory (memory, memory.size): cannot have 256 MiB"},
        {"run " + kBudget + kShort + " --set 'memory.size=1 MiB' --quiet", 200000,
         "surfvp: out of memory: mapping the image and video plugin "}};
    for (const auto& [args, kib, says] : cases) {
        const std::string err = fresh_path("oom.err");
        const int status =
            std::system(("bash -c \"ulimit -v " + std::to_string(kib) + "; SURFVP_CACHE=off exec " +
                         std::string(SURFVP_BINARY) + " " + args + " --out " + fresh_dir("oom") + "\" 2>" + err)
                            .c_str());
        EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 5) << args << ": " << slurp(err);
        EXPECT_NE(slurp(err).find(says), std::string::npos) << args << ": " << slurp(err);
    }
}

// A truncated image and video plugin is refused before the loader maps it (it faulted with
// SIGBUS when a segment lay past the file's end), naming the plugin and what is wrong.
TEST(Environment, ATruncatedMediaPluginIsRefusedNotMapped) {
    const std::string plugin =
        slurp(std::string(SURFVP_BINARY).substr(0, std::string(SURFVP_BINARY).rfind('/')) + "/libsurfvp_media.so");
    ASSERT_GT(plugin.size(), 8000u);
    std::string segments_cut = plugin.substr(0, plugin.size() / 2);
    const uint64_t none = 0;  // no section headers: only the segments can tell the cut
    std::memcpy(segments_cut.data() + offsetof(Elf64_Ehdr, e_shoff), &none, sizeof none);
    std::memset(segments_cut.data() + offsetof(Elf64_Ehdr, e_shnum), 0, sizeof(Elf64_Half));
    const std::string dir = fresh_dir("plugin");
    for (const auto& [bytes, says] : std::vector<std::pair<std::string, std::string>>{
             {plugin.substr(0, plugin.size() / 2), "cut short (section headers)"},
             {segments_cut, "cut short: segment "},
             {plugin.substr(0, 40), "not a 64-bit ELF shared object"},
             {"#!/bin/sh\n", "not a 64-bit ELF shared object"}}) {
        const std::string file = write_file(dir, "libsurfvp_media.so", bytes);
        const std::string err = fresh_path("plugin.err");
        const int status =
            std::system(("SURFVP_CACHE=off SURFVP_MEDIA_PLUGIN=" + file + " " + std::string(SURFVP_BINARY) + " run " +
                         kBudget + kShort + " --quiet --out " + dir + "/out 2>" + err)
                            .c_str());
        EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2) << says << ": " << slurp(err);
        EXPECT_NE(slurp(err).find("cannot load the image and video plugin " + file + ": " + says), std::string::npos)
            << slurp(err);
    }
    // A FIFO under the plugin's name: refused without opening it (opening would wait for a writer).
    const std::string fifo = dir + "/fifo.so";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string err = fresh_path("plugin_fifo.err");
    const int status =
        std::system(("SURFVP_CACHE=off SURFVP_MEDIA_PLUGIN=" + fifo + " timeout 60 " + std::string(SURFVP_BINARY) +
                     " run " + kBudget + kShort + " --quiet --out " + dir + "/out 2>" + err)
                        .c_str());
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2) << slurp(err);
    EXPECT_NE(slurp(err).find(fifo + ": not a readable regular file"), std::string::npos) << slurp(err);
}

}  // namespace
}  // namespace surfvp::test
