// The output folder's publication: a run's files go into a run folder of its own and become the
// outputs in one step; what the folder held before is never trusted, and nothing surfvp did not
// write, inside the folder or outside it, is removed.
#include <filesystem>
#include <gtest/gtest.h>
#include <set>

#include "cli.h"
#include "platform/run/output_folder.h"
#include "platform/scenario/config.h"

namespace surfvp::test {
namespace {
namespace fs = std::filesystem;

// One run into `folder`: `files` written into its staging folder, then published.
void publish_run(const std::string& folder, const std::set<std::string>& files) {
    OutputFolder out(folder);
    for (const std::string& f : files) {
        fs::create_directories((out.staging() / f).parent_path());
        write_file(out.staging().string(), f, "run of " + std::to_string(files.size()) + ": " + f);
    }
    out.publish();
}

// The files a reader sees in `dir`: its visible names, links followed.
std::set<std::string> outputs_in(const std::string& dir) {
    std::set<std::string> files;
    for (const auto& top : fs::directory_iterator(dir)) {
        if (top.path().filename().string().front() == '.') continue;
        if (top.is_regular_file()) files.insert(top.path().filename().string());
        if (top.is_directory())
            for (const auto& e : fs::recursive_directory_iterator(top.path()))
                if (e.is_regular_file())
                    files.insert((top.path().filename() / e.path().lexically_relative(top.path())).string());
    }
    return files;
}

size_t runs_in(const std::string& dir) {
    return size_t(std::distance(fs::directory_iterator(dir + "/.surfvp-runs"), fs::directory_iterator{}));
}

TEST(OutputFolder, ANewRunReplacesThePreviousSetWholeAndKeepsOneRunFolder) {
    const std::string out = fresh_dir("publish_whole");
    publish_run(out, {"report.json", "trace.vcd", "keypoints/frame_0000.surf", "keypoints/frame_0001.surf"});
    publish_run(out, {"report.json", "keypoints/frame_0000.surf"});
    EXPECT_EQ(outputs_in(out), (std::set<std::string>{"report.json", "keypoints/frame_0000.surf"}));
    EXPECT_EQ(slurp(out + "/keypoints/frame_0000.surf"), "run of 2: keypoints/frame_0000.surf");
    EXPECT_FALSE(fs::exists(fs::symlink_status(out + "/trace.vcd")));  // its link is gone too
    EXPECT_EQ(runs_in(out), 1u);
    EXPECT_TRUE(fs::is_symlink(out + "/report.json"));
}

TEST(OutputFolder, AManifestNamingFilesOutsideTheFolderIsNeverActedOn) {
    const std::string root = fresh_dir("publish_manifest"), out = root + "/out";
    write_file(root, "victim.txt", "keep me");
    fs::create_directories(out);
    write_file(out, ".surfvp-outputs", "../victim.txt\n" + root + "/victim.txt\nmine.txt\n");
    write_file(out, "mine.txt", "mine");
    publish_run(out, {"report.json"});
    EXPECT_EQ(slurp(root + "/victim.txt"), "keep me");
    EXPECT_EQ(slurp(out + "/mine.txt"), "mine");
    EXPECT_FALSE(fs::exists(out + "/.surfvp-outputs"));  // an older surfvp's list, not read
    EXPECT_EQ(outputs_in(out), (std::set<std::string>{"mine.txt", "report.json"}));
}

TEST(OutputFolder, AnOlderSurfvpsOutputsAreReplacedAndTheUsersFilesKept) {
    const std::string out = fresh_dir("publish_legacy");
    fs::create_directories(out + "/keypoints");
    for (const char* f : {"report.json", "report.md", "trace.vcd", "notes.txt"}) write_file(out, f, "old");
    write_file(out + "/keypoints", "frame_0000.surf", "old");
    write_file(out + "/keypoints", "frame_0001.surf", "old");
    publish_run(out, {"report.json", "keypoints/frame_0000.surf"});
    EXPECT_EQ(outputs_in(out), (std::set<std::string>{"notes.txt", "report.json", "keypoints/frame_0000.surf"}));
    EXPECT_EQ(slurp(out + "/notes.txt"), "old");
}

TEST(OutputFolder, AFolderTheUserMadeUnderAnOutputsNameIsRefusedBeforeAnythingChanges) {
    const std::string out = fresh_dir("publish_user_folder");
    publish_run(out, {"report.json"});
    fs::remove(out + "/report.json");
    fs::create_directories(out + "/keypoints");
    write_file(out + "/keypoints", "plan.txt", "mine");
    try {
        publish_run(out, {"report.json", "keypoints/frame_0000.surf"});
        FAIL() << "published over the user's folder";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("keypoints is a folder surfvp did not write"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(slurp(out + "/keypoints/plan.txt"), "mine");
    EXPECT_EQ(runs_in(out), 1u);  // the refused run's folder is gone, the previous one stays
}

TEST(OutputFolder, FilesPutIntoAPublishedFolderKeepTheirRunFolder) {
    const std::string out = fresh_dir("publish_user_file_inside");
    publish_run(out, {"keypoints/frame_0000.surf", "keypoints/frame_0001.surf"});
    write_file(out + "/keypoints", "mine.txt", "mine");
    publish_run(out, {"keypoints/frame_0000.surf"});
    EXPECT_EQ(outputs_in(out), (std::set<std::string>{"keypoints/frame_0000.surf"}));
    EXPECT_EQ(runs_in(out), 2u);  // the earlier run's folder, with mine.txt, is kept
    bool found = false;
    for (const auto& run : fs::directory_iterator(out + "/.surfvp-runs"))
        found = found || (fs::exists(run.path() / "keypoints/mine.txt") &&
                          slurp((run.path() / "keypoints/mine.txt").string()) == "mine");
    EXPECT_TRUE(found);
}

TEST(OutputFolder, AHiddenFolderInStagingIsNotPublished) {
    const std::string out = fresh_dir("publish_hidden");
    publish_run(out, {"table/a.txt", "table/.scratch/point0.json", ".points/p.json"});
    EXPECT_EQ(outputs_in(out), (std::set<std::string>{"table/a.txt"}));
    EXPECT_FALSE(fs::exists(out + "/table/.scratch"));
}

TEST(OutputFolder, LinksAndRunFoldersSomeoneElseMadeAreNeverFollowed) {
    const std::string root = fresh_dir("publish_foreign_links"), out = root + "/out", elsewhere = root + "/elsewhere";
    fs::create_directories(elsewhere);
    write_file(elsewhere, "precious.txt", "keep me");
    fs::create_directories(out);
    fs::create_directory_symlink(elsewhere, out + "/.surfvp-current");
    fs::create_symlink(elsewhere + "/precious.txt", out + "/report.md");
    publish_run(out, {"report.json"});
    EXPECT_EQ(slurp(elsewhere + "/precious.txt"), "keep me");
    EXPECT_EQ(outputs_in(out),
              (std::set<std::string>{"report.json", "report.md"}));  // a link not of surfvp's form is the user's
    const std::string other = root + "/other";
    fs::create_directories(other);
    fs::create_directory_symlink(elsewhere, other + "/.surfvp-runs");
    EXPECT_THROW(OutputFolder{other}, ConfigError);
    EXPECT_EQ(slurp(elsewhere + "/precious.txt"), "keep me");
}

// The names left in `dir`, hidden ones included.
std::set<std::string> names_in(const std::string& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

TEST(OutputFolder, WhatWouldStopThePublicationIsRefusedBeforeAnythingIsMade) {
    const std::string out = fresh_dir("publish_refused_first");
    fs::create_directories(out + "/keypoints");
    write_file(out + "/keypoints", "plan.txt", "mine");
    EXPECT_THROW(OutputFolder(out, {"report.json", "keypoints"}), ConfigError);
    fs::remove_all(out + "/keypoints");
    fs::create_directories(out + "/.surfvp-current");
    write_file(out + "/.surfvp-current", "report.json", "{}");
    try {
        OutputFolder refused(out, {"report.json"});
        FAIL() << "took a .surfvp-current that is a folder";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(".surfvp-current is a folder, not surfvp's link"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(names_in(out), (std::set<std::string>{".surfvp-current"}));  // no lock, no run folders, no links
}

TEST(OutputFolder, ARunThatPublishedNothingLeavesNoTrace) {
    const std::string root = fresh_dir("publish_nothing"), out = root + "/new";
    { OutputFolder unpublished(out); }
    EXPECT_FALSE(fs::exists(out));  // the folder it made, gone with its lock and run folders
    fs::create_directories(out);
    write_file(out, "mine.txt", "mine");
    { OutputFolder unpublished(out); }
    EXPECT_EQ(names_in(out), (std::set<std::string>{"mine.txt"}));
    publish_run(out, {"report.json"});
    { OutputFolder unpublished(out); }
    EXPECT_EQ(names_in(out), (std::set<std::string>{"mine.txt", "report.json", ".surfvp-current", ".surfvp-runs",
                                                    ".surfvp.lock"}));  // a published set stays whole
}

TEST(OutputFolder, ALockThatIsAHardLinkIsRefusedAndTheOtherNameKeepsItsText) {
    const std::string root = fresh_dir("publish_hard_lock"), out = root + "/out";
    fs::create_directories(out);
    write_file(root, "victim.txt", "keep me");
    fs::create_hard_link(root + "/victim.txt", out + "/.surfvp.lock");
    try {
        OutputFolder refused(out);
        FAIL() << "took a lock with two names";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("has 2 names (a hard link"), std::string::npos) << e.what();
    }
    EXPECT_EQ(slurp(root + "/victim.txt"), "keep me");
}

TEST(OutputFolder, AStaleLockIsReadOnlyAsFarAsAPidAndItsTextNeverShown) {
    const std::string out = fresh_dir("publish_odd_lock");
    write_file(out, ".surfvp.lock", "\x1b[2J not a pid\n");
    testing::internal::CaptureStderr();
    publish_run(out, {"report.json"});
    const std::string said = testing::internal::GetCapturedStderr();
    EXPECT_NE(said.find("took over the stale lock of a run that did not finish (pid ?, no longer running)"),
              std::string::npos)
        << said;
    EXPECT_EQ(said.find('\x1b'), std::string::npos);
    EXPECT_EQ(slurp(out + "/report.json"), "run of 1: report.json");
}

}  // namespace
}  // namespace surfvp::test
