// The output folder's publication: a folder of outputs goes into place whole when the folder
// it replaces holds only the previous run's outputs, file by file when it holds anything else;
// either way the folder ends with exactly this run's outputs and every file surfvp did not write.
#include <filesystem>
#include <gtest/gtest.h>
#include <set>
#include <sys/stat.h>

#include "cli.h"
#include "platform/run/output_folder.h"

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

// Every file under `dir`, hidden ones too, relative to it.
std::set<std::string> everything_under(const std::string& dir) {
    std::set<std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) files.insert(e.path().lexically_relative(dir).string());
    return files;
}

ino_t inode(const std::string& path) {
    struct stat s {};
    return ::stat(path.c_str(), &s) == 0 ? s.st_ino : 0;
}

TEST(OutputFolder, AFolderOfOutputsReplacesThePreviousRunsWhole) {
    const std::string out = fresh_dir("publish_whole");
    publish_run(out, {"report.json", "keypoints/frame_0000.surf", "keypoints/frame_0001.surf", "keypoints/frame_0002.surf"});
    const ino_t first = inode(out + "/keypoints");
    publish_run(out, {"report.json", "keypoints/frame_0000.surf", "keypoints/frame_0001.surf"});
    EXPECT_EQ(everything_under(out), (std::set<std::string>{".surfvp-outputs", ".surfvp.lock", "report.json",
                                                            "keypoints/frame_0000.surf", "keypoints/frame_0001.surf"}));
    EXPECT_NE(inode(out + "/keypoints"), first);  // the staging folder's, moved in
    EXPECT_EQ(slurp(out + "/keypoints/frame_0001.surf"), "run of 3: keypoints/frame_0001.surf");
}

TEST(OutputFolder, AFolderHoldingAFileSurfvpDidNotWriteIsUpdatedFileByFile) {
    const std::string out = fresh_dir("publish_by_file");
    publish_run(out, {"keypoints/frame_0000.surf", "keypoints/frame_0001.surf"});
    write_file(out + "/keypoints", "mine.txt", "mine");
    fs::create_directories(out + "/keypoints/.hidden");
    write_file(out + "/keypoints/.hidden", "notes", "also mine");
    const ino_t first = inode(out + "/keypoints");
    publish_run(out, {"keypoints/frame_0000.surf"});
    EXPECT_EQ(inode(out + "/keypoints"), first);
    EXPECT_EQ(everything_under(out), (std::set<std::string>{".surfvp-outputs", ".surfvp.lock", "keypoints/frame_0000.surf",
                                                            "keypoints/mine.txt", "keypoints/.hidden/notes"}));
    EXPECT_EQ(slurp(out + "/keypoints/frame_0000.surf"), "run of 1: keypoints/frame_0000.surf");
    EXPECT_EQ(slurp(out + "/keypoints/mine.txt"), "mine");
}

TEST(OutputFolder, AHiddenFolderInStagingIsNotPublished) {
    const std::string out = fresh_dir("publish_hidden");
    publish_run(out, {"table/a.txt", "table/.scratch/point0.json", ".points/p.json"});
    EXPECT_EQ(everything_under(out), (std::set<std::string>{".surfvp-outputs", ".surfvp.lock", "table/a.txt"}));
    EXPECT_EQ(slurp(out + "/.surfvp-outputs"), "table/a.txt\n");
}

}  // namespace
}  // namespace surfvp::test
