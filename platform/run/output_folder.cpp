#include "platform/run/output_folder.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <regex>
#include <csignal>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "models/host/atomic_file.h"
#include "platform/scenario/config.h"

namespace surfvp {
namespace fs = std::filesystem;
namespace {

constexpr const char* kLock = ".surfvp.lock";
constexpr const char* kRuns = ".surfvp-runs";
constexpr const char* kCurrent = ".surfvp-current";
constexpr const char* kRunList = ".surfvp-files";  // in a run folder: the files the run wrote

// What an older surfvp (before the run folders) wrote at the folder's top, by fixed names: a
// folder it left is replaced once by the links. Its manifest's names are never acted on.
const std::set<std::string> kLegacyOutputs = {"report.json", "report.md",       "report.html",    "config.yaml",
                                              "frames.csv",  "tornado.svg",     "trace.vcd",      "trace.perfetto.json",
                                              "trace.gtkw",  "trace.tasks.txt", ".surfvp-outputs"};
constexpr const char* kLegacyStagingPrefix = ".partial-";

[[noreturn]] void refuse(const fs::path& folder, const std::string& why) {
    throw EnvironmentError(fmt::format("--out {}: {}", folder.string(), why));
}

bool hidden(const fs::path& p) { return p.filename().string().front() == '.'; }

fs::file_type type_of(const fs::path& p) {
    std::error_code ignored;
    return fs::symlink_status(p, ignored).type();
}

// What an output's link in the folder points to.
fs::path link_target(const std::string& name) { return fs::path(kCurrent) / name; }

// The output a link of ours stands for, or "" for anything else (a file, a foreign link).
std::string output_of_link(const fs::path& p) {
    if (type_of(p) != fs::file_type::symlink) return "";
    std::error_code error;
    const fs::path target = fs::read_symlink(p, error);
    return !error && target == link_target(p.filename().string()) ? p.filename().string() : "";
}

// The run folder .surfvp-current names (its name in .surfvp-runs), or "" when it names
// anything else: a link someone else made is replaced, never followed.
std::string current_run(const fs::path& folder) {
    std::error_code error;
    const fs::path target = fs::read_symlink(folder / kCurrent, error);
    if (error || target.parent_path() != kRuns) return "";
    const std::string run = target.filename().string();
    return run.empty() || run == "." || run == ".." ? "" : run;
}

// Removes every hidden entry under `dir` (a verdict's scratch): not outputs.
void remove_hidden(const fs::path& dir) {
    std::error_code error;
    std::vector<fs::path> gone;
    for (auto it = fs::recursive_directory_iterator(dir, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error))
        if (hidden(it->path())) {
            gone.push_back(it->path());
            it.disable_recursion_pending();
        }
    for (const fs::path& p : gone) fs::remove_all(p, error);
}

// Whether a process with this pid runs (one of another user's counts).
bool alive(const std::string& pid) {
    char* end = nullptr;
    const long n = std::strtol(pid.c_str(), &end, 10);
    return n > 0 && *end == '\0' && (::kill(pid_t(n), 0) == 0 || errno == EPERM);
}

// The pid a lock names: its first bytes if they are digits, else "?" (a lock is read no further
// than a pid's length, and none of its text reaches the terminal).
std::string pid_in(int fd) {
    char text[24] = {};
    const ssize_t got = ::pread(fd, text, sizeof text - 1, 0);
    std::string pid(text, size_t(std::max<ssize_t>(got, 0)));
    pid = pid.substr(0, pid.find('\n'));
    const bool digits = !pid.empty() && pid.size() < 20 && pid.find_first_not_of("0123456789") == std::string::npos;
    return got <= 0 ? "" : digits ? pid : "?";
}

// Whether `fd` and `path` are one file: a lock taken on a file that another run removed and
// made again in the meantime is no lock at all.
bool same_file(int fd, const fs::path& path) {
    struct stat a {
    }, b{};
    return ::fstat(fd, &a) == 0 && ::lstat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

bool empty_folder(const fs::path& dir) {
    std::error_code error;
    return type_of(dir) == fs::file_type::directory && fs::is_empty(dir, error) && !error;
}

// Every regular file under `dir` but its list, relative to it.
std::set<std::string> files_of(const fs::path& dir) {
    std::set<std::string> files;
    std::error_code error;
    for (auto it = fs::recursive_directory_iterator(dir, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error))
        if (type_of(it->path()) == fs::file_type::regular && it->path().filename() != kRunList)
            files.insert(it->path().lexically_relative(dir).string());
    return files;
}

// Removes a run folder that is not the current one, unless someone put files into it through
// the links (a note beside the keypoints): then it stays, and the warning names them. A run
// folder without its list is a killed run's staging, which only that run wrote into.
void remove_run(const fs::path& run) {
    std::ifstream in(run / kRunList);
    const std::string listed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.is_open()) {
        std::set<std::string> ours;
        for (size_t at = 0, end; (end = listed.find('\n', at)) != std::string::npos; at = end + 1)
            ours.insert(listed.substr(at, end - at));
        std::vector<std::string> theirs;
        for (const std::string& f : files_of(run))
            if (!ours.count(f)) theirs.push_back(f);
        if (!theirs.empty()) {
            std::fprintf(stderr, "surfvp: warning: kept %s: it holds files surfvp did not write (%s)\n", run.c_str(),
                         fmt::format("{}", fmt::join(theirs, ", ")).c_str());
            return;
        }
    }
    std::error_code ignored;
    fs::remove_all(run, ignored);
}

void remove_runs_but(const fs::path& runs, const std::string& kept) {
    std::vector<fs::path> others;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(runs, error))
        if (entry.path().filename() != kept) others.push_back(entry.path());
    for (const fs::path& run : others) remove_run(run);
}

// Whether `dir` is a folder an older surfvp wrote: only its files, by its names (keypoints,
// reports, traces), none hidden, no links.
bool legacy_folder(const fs::path& dir) {
    static const std::regex keypoints(R"(frame_[0-9]+\.(surf|key))");
    std::error_code error;
    for (auto it = fs::recursive_directory_iterator(dir, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error)) {
        const fs::file_type t = type_of(it->path());
        const std::string name = it->path().filename().string();
        if (hidden(it->path()) || (t != fs::file_type::directory && t != fs::file_type::regular) ||
            (t == fs::file_type::regular && !kLegacyOutputs.count(name) && !std::regex_match(name, keypoints)))
            return false;
    }
    return !error;
}

// A folder the user made under one of `names` (one an older surfvp wrote is replaced instead).
void refuse_users_folders(const fs::path& folder, const std::set<std::string>& names) {
    for (const std::string& name : names)
        if (type_of(folder / name) == fs::file_type::directory && !legacy_folder(folder / name))
            throw ConfigError(
                fmt::format("--out {}: {} is a folder surfvp did not write; move it away, or give another --out",
                            folder.string(), (folder / name).string()));
}

// A .surfvp-current that is a folder: the outputs' links would lead into it.
void refuse_current_folder(const fs::path& folder) {
    if (type_of(folder / kCurrent) == fs::file_type::directory)
        throw ConfigError(fmt::format("--out {}: {} is a folder, not surfvp's link; remove it", folder.string(),
                                      (folder / kCurrent).string()));
}

}  // namespace

OutputFolder::OutputFolder(const fs::path& folder, const std::set<std::string>& outputs) : folder_(folder) {
    check_before_writing(outputs);
    std::error_code error;
    made_folder_ = type_of(folder_) == fs::file_type::not_found;
    fs::create_directories(folder_, error);
    if (error || !fs::is_directory(folder_))
        refuse(folder_, "cannot create the folder: " + (error ? error.message() : "a file is in the way"));
    try {
        lock();
        // Holding the lock, every run folder but the current one is a killed run's.
        const fs::path runs = folder_ / kRuns;
        made_runs_ = type_of(runs) == fs::file_type::not_found && fs::create_directory(runs, error);
        if (error) refuse(folder_, "cannot create " + runs.string() + ": " + error.message());
        remove_runs_but(runs, current_run(folder_));
        for (const auto& entry : fs::directory_iterator(folder_, error)) {
            const std::string name = entry.path().filename().string();
            const fs::file_type type = type_of(entry.path());
            if ((name.rfind(kLegacyStagingPrefix, 0) == 0 &&
                 type == fs::file_type::directory) ||  // an older surfvp's killed run
                ((name.rfind(".surfvp-link-", 0) == 0 || name.rfind(".surfvp-current-", 0) == 0) &&
                 type == fs::file_type::symlink))
                fs::remove_all(entry.path(), error);  // a killed run's link not yet in place
            else if (!output_of_link(entry.path()).empty() && !fs::exists(entry.path(), error))
                fs::remove(entry.path(), error);  // killed between its links and their switch
        }
        const auto now = std::chrono::system_clock::now().time_since_epoch();
        staging_ =
            runs / fmt::format("{}-{}", ::getpid(), std::chrono::duration_cast<std::chrono::microseconds>(now).count());
        fs::create_directory(staging_, error);
        if (error) refuse(folder_, "cannot create " + staging_.string() + ": " + error.message());
    } catch (...) {
        undo_unpublished();
        throw;
    }
}

// What would stop the publication, found before anything is written or simulated: a folder of
// the user's under an output's name, a .surfvp-current that is a folder (the outputs' links
// would lead into it), a .surfvp-runs that is not a folder (removing through a link would reach
// outside).
void OutputFolder::check_before_writing(const std::set<std::string>& outputs) const {
    refuse_users_folders(folder_, outputs);
    refuse_current_folder(folder_);
    const fs::file_type runs = type_of(folder_ / kRuns);
    if (runs != fs::file_type::not_found && runs != fs::file_type::directory)
        throw ConfigError(fmt::format("--out {}: {} is not a folder surfvp made (a link or a file); remove it",
                                      folder_.string(), (folder_ / kRuns).string()));
}

// flock is released when its holder ends, so a lock file no process holds is stale, whatever
// pid it names. Another user's lock file cannot be opened for writing: it is locked through a
// read-only descriptor and taken over, made again as ours where the folder lets us remove it.
void OutputFolder::lock() {
    const fs::path lock = folder_ / kLock;
    struct stat st {};
    const bool exists = ::lstat(lock.c_str(), &st) == 0;
    if (exists && !S_ISREG(st.st_mode))
        throw ConfigError(fmt::format("--out {}: {} is not a regular file (surfvp's lock is); remove it",
                                      folder_.string(), lock.string()));
    if (exists && st.st_nlink != 1)  // a hard link: emptying it would empty a file elsewhere
        throw ConfigError(fmt::format("--out {}: {} has {} names (a hard link; surfvp's lock has one); remove it",
                                      folder_.string(), lock.string(), st.st_nlink));
    lock_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    made_lock_ = !exists && lock_ >= 0;
    const bool foreign = lock_ < 0 && errno == EACCES;
    if (foreign) lock_ = ::open(lock.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (lock_ < 0) refuse(folder_, fmt::format("cannot create {} ({})", lock.string(), std::strerror(errno)));
    const std::string previous = pid_in(lock_);
    auto busy = [&] {
        if (lock_ >= 0) ::close(lock_);
        lock_ = -1;
        made_lock_ = false;
        refuse(folder_, fmt::format("another surfvp run (pid {}) is writing there; wait for it or give another --out",
                                    previous.empty() ? "?" : previous));
    };
    if (::flock(lock_, LOCK_EX | LOCK_NB) != 0 || !same_file(lock_, lock)) busy();
    if (::fstat(lock_, &st) != 0 || st.st_nlink != 1) busy();  // linked elsewhere since: not ours to empty
    if (!foreign && !previous.empty())  // a run that ends empties its lock: this one's was killed
        std::fprintf(stderr,
                     "surfvp: warning: --out %s: took over the stale lock of a run that did not finish (pid %s, %s)\n",
                     folder_.c_str(), previous.c_str(), alive(previous) ? "no longer holding it" : "no longer running");
    if (foreign) {
        std::fprintf(stderr, "surfvp: warning: --out %s: took over the stale lock of another user's run (pid %s, %s)\n",
                     folder_.c_str(), previous.empty() ? "?" : previous.c_str(),
                     alive(previous) ? "no longer holding it" : "no longer running");
        if (::unlink(lock.c_str()) != 0) return;  // a folder that keeps others' files (sticky): locked through theirs
        ::close(lock_);
        lock_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
        made_lock_ = lock_ >= 0;
        if (lock_ < 0 || ::flock(lock_, LOCK_EX | LOCK_NB) != 0) busy();  // another run made it first
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(lock_, 0) != 0 || ::pwrite(lock_, pid.data(), pid.size(), 0) != ssize_t(pid.size()))
        refuse(folder_, fmt::format("cannot write {} ({})", lock.string(), std::strerror(errno)));
}

// A run that published nothing into a folder it made leaves no trace: its lock (removed while
// held, so a run that opened it meanwhile finds it is not the file's name any more), its
// .surfvp-runs and the folder itself, each only where nothing else came into it.
void OutputFolder::undo_unpublished() noexcept {
    std::error_code ignored;
    if (!staging_.empty()) fs::remove_all(staging_, ignored);
    if (made_runs_ && empty_folder(folder_ / kRuns)) fs::remove(folder_ / kRuns, ignored);
    if (made_lock_ && type_of(folder_ / kRuns) == fs::file_type::not_found) ::unlink((folder_ / kLock).c_str());
    if (lock_ >= 0) {
        [[maybe_unused]] const int emptied = ::ftruncate(lock_, 0);  // finished: nothing stale
        ::close(lock_);                                              // releases the lock
        lock_ = -1;
    }
    if (made_folder_ && empty_folder(folder_)) fs::remove(folder_, ignored);
}

OutputFolder::~OutputFolder() {
    if (!published_) {
        undo_unpublished();
        return;
    }
    [[maybe_unused]] const int emptied = ::ftruncate(lock_, 0);  // finished: nothing stale (another user's stays)
    ::close(lock_);                                              // releases the lock
}

void OutputFolder::publish_files(const std::vector<std::pair<std::string, std::string>>& files) {
    try {
        for (const auto& [name, text] : files) write_file_atomically(staging_ / name, text);
        publish();
    } catch (const EnvironmentError& e) {
        throw EnvironmentError(
            fmt::format("{}; what was in {} before is as it was", as_published(e.what()), folder_.string()));
    }
}

void OutputFolder::publish() {
    remove_hidden(staging_);
    std::set<std::string> names;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(staging_, error)) names.insert(entry.path().filename().string());
    for (auto it = fs::recursive_directory_iterator(staging_, error);
         !error && it != fs::recursive_directory_iterator(); it.increment(error))
        if (it->path().extension() == ".gtkw") name_published_files(it->path());
    if (error) refuse(folder_, fmt::format("cannot read {}: {}", staging_.string(), error.message()));
    std::string list;
    for (const std::string& f : files_of(staging_)) list += f + "\n";
    write_file_atomically(staging_ / kRunList, list);
    link_outputs(names);
    switch_current();
    published_ = true;
    remove_stale(names);
}

// Each output's name becomes a link through .surfvp-current. Before the switch a new name's
// link leads nowhere (or to the previous run's file of that name), so the folder still holds
// the previous set. A file of that name (an older surfvp's, or one the user put there, as a
// run always replaced it) is replaced by its link; a folder only when an older surfvp wrote
// it: one the user made is refused before anything changes.
void OutputFolder::link_outputs(const std::set<std::string>& names) const {
    refuse_users_folders(folder_, names);  // checked before the run too; a folder made since
    for (const std::string& name : names) {
        const fs::path at = folder_ / name;
        if (!output_of_link(at).empty()) continue;
        const fs::path tmp = folder_ / fmt::format(".surfvp-link-{}", ::getpid());
        std::error_code error;
        fs::remove(tmp, error);
        fs::create_symlink(link_target(name), tmp, error);
        if (!error && type_of(at) == fs::file_type::directory) {
            fs::remove_all(at, error);  // an older surfvp's folder of outputs
        }
        if (!error) fs::rename(tmp, at, error);
        if (error) refuse(folder_, fmt::format("cannot link {} into place: {}", name, error.message()));
    }
}

// The one step: .surfvp-current renamed to name this run's folder.
void OutputFolder::switch_current() const {
    const fs::path next = folder_ / fmt::format(".surfvp-current-{}", ::getpid()), current = folder_ / kCurrent;
    refuse_current_folder(folder_);  // checked before the run too; a folder made since
    std::error_code error;
    fs::remove(next, error);
    fs::create_symlink(fs::path(kRuns) / staging_.filename(), next, error);
    if (!error) fs::rename(next, current, error);
    if (error) refuse(folder_, fmt::format("cannot switch {} to this run: {}", current.string(), error.message()));
}

// After the switch: links of outputs this run did not write, the run folders before it, and
// what an older surfvp left under its fixed names.
void OutputFolder::remove_stale(const std::set<std::string>& names) const {
    std::error_code error;
    std::vector<fs::path> gone;
    for (const auto& entry : fs::directory_iterator(folder_, error)) {
        const std::string name = entry.path().filename().string(), output = output_of_link(entry.path());
        if ((!output.empty() && !names.count(output)) ||
            (output.empty() && kLegacyOutputs.count(name) && !names.count(name) &&
             type_of(entry.path()) == fs::file_type::regular))
            gone.push_back(entry.path());
    }
    for (const fs::path& p : gone) fs::remove_all(p, error);
    remove_runs_but(folder_ / kRuns, staging_.filename().string());
}

// GTKWave's save file names the VCD by its absolute path: the one it is published under.
void OutputFolder::name_published_files(const fs::path& file) const {
    std::ifstream in(file, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    write_file_atomically(file, as_published(text));
}

std::string OutputFolder::as_published(std::string message) const {
    const std::string from = staging_.string(), to = folder_.string();
    for (size_t at = message.find(from); at != std::string::npos; at = message.find(from, at + to.size()))
        message.replace(at, from.size(), to);
    return message;
}

}  // namespace surfvp
