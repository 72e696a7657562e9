#pragma once
// A run's output folder, all or nothing. The run holds a lock on the folder for its whole
// length (a second run given the same folder is refused, naming the first one's pid), writes
// every file into a staging folder of its own inside it, and at the end moves its complete
// set into place, removing what the previous run there wrote that this one did not write
// again (its keypoints of frames that no longer exist, traces it did not ask for). A run that
// fails or is killed leaves the previous output as it was; the staging folder of a killed
// run is removed by the next run that takes the lock. Files surfvp did not write are never
// touched. The list of what a run wrote is kept in the folder (.surfvp-outputs).
#include <filesystem>
#include <set>
#include <string>

namespace surfvp {

class OutputFolder {
public:
    // Creates and locks `folder`; throws EnvironmentError when it cannot be created or
    // locked, or another run holds it.
    explicit OutputFolder(const std::filesystem::path& folder);
    ~OutputFolder();  // an unpublished staging folder is removed; the lock is released
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;

    const std::filesystem::path& folder() const { return folder_; }
    const std::filesystem::path& staging() const { return staging_; }

    // Moves everything written into staging() into place and removes the previous run's
    // files that are not among them. Throws EnvironmentError.
    void publish();

    // `message` with staging paths shown as the files they were to become.
    std::string as_published(std::string message) const;

private:
    std::set<std::string> previous_outputs() const;
    // The staging folder's folders moved into place whole (their names).
    std::set<std::string> move_folders(const std::set<std::string>& written, const std::set<std::string>& previous) const;
    void name_published_files(const std::filesystem::path& file) const;

    std::filesystem::path folder_, staging_;
    int lock_ = -1;
    bool published_ = false;
};

}  // namespace surfvp
