#pragma once
// A run's output folder, all or nothing, whatever instant a kill lands. The run holds a lock
// on the folder for its whole length (a second run given the same folder is refused, naming
// the first one's pid), writes every file into a run folder of its own
// (.surfvp-runs/<pid>), and publishes it by renaming one symbolic link: .surfvp-current names
// the run folder whose files are the outputs, and each output's name in the folder is a link
// through it (report.json -> .surfvp-current/report.json). Switching .surfvp-current changes
// every output at once. A name only one of the two runs wrote leads nowhere for a moment
// around the switch (before it, the new run's link; after it, the old run's until removed):
// a kill in that moment leaves such a dangling link, which reads as no file, and the next run
// that takes the lock removes it. Every name that resolves is one run's. A run that fails or
// is killed leaves the previous set as it was; its run folder is removed by the next run that
// takes the lock.
//
// Nothing the folder holds is trusted: surfvp removes only links of exactly that form, its
// own run folders and, once, the files an older surfvp wrote under its fixed names. Files
// surfvp did not write are never touched, and nothing outside the folder is.
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace surfvp {

class OutputFolder {
public:
    // Creates and locks `folder`; throws EnvironmentError when it cannot be created or
    // locked, or another run holds it, and ConfigError when it holds what surfvp cannot
    // publish over: a folder of the user's under one of `outputs` (the top-level names the
    // command writes), a `.surfvp-current` or `.surfvp-runs` that is not surfvp's, a lock that
    // is not a plain file of one name. A refusal leaves the folder as it was.
    explicit OutputFolder(const std::filesystem::path& folder, const std::set<std::string>& outputs = {});
    // An unpublished run folder is removed; the lock is released. A run that published nothing
    // removes what it made (the lock, .surfvp-runs, the folder) where nothing else is there.
    ~OutputFolder();
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;

    const std::filesystem::path& folder() const { return folder_; }
    const std::filesystem::path& staging() const { return staging_; }

    // Makes everything written into staging() the folder's outputs in one step and removes
    // the links of the previous run's outputs that are not among them. Throws
    // EnvironmentError.
    void publish();
    // Writes each (name, text) into staging() and publishes them; an EnvironmentError says that
    // what the folder held before is as it was. For the studies that write a few pages at once.
    void publish_files(const std::vector<std::pair<std::string, std::string>>& files);

    // `message` with staging paths shown as the files they were to become.
    std::string as_published(std::string message) const;

private:
    void check_before_writing(const std::set<std::string>& outputs) const;
    void lock();
    void undo_unpublished() noexcept;
    void link_outputs(const std::set<std::string>& names) const;
    void switch_current() const;
    void remove_stale(const std::set<std::string>& names) const;
    void name_published_files(const std::filesystem::path& file) const;

    std::filesystem::path folder_, staging_;
    int lock_ = -1;
    bool published_ = false;
    bool made_folder_ = false, made_lock_ = false, made_runs_ = false;  // what a run that published nothing undoes
};

}  // namespace surfvp
