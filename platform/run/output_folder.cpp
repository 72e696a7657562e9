#include "platform/run/output_folder.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <sys/file.h>
#include <unistd.h>

#include "models/common/atomic_file.h"

namespace surfvp {
namespace fs = std::filesystem;
namespace {

constexpr const char* kLock = ".surfvp.lock";
constexpr const char* kManifest = ".surfvp-outputs";
constexpr const char* kStagingPrefix = ".partial-";

// What surfvp writes into a folder, for one written before the manifest existed.
const std::set<std::string> kKnownOutputs = {"report.json", "report.md",        "report.html",          "config.yaml",
                                             "frames.csv",  "tornado.svg",      "trace.vcd",            "trace.perfetto.json",
                                             "trace.gtkw",  "trace.tasks.txt"};

[[noreturn]] void refuse(const fs::path& folder, const std::string& why) {
    throw EnvironmentError(fmt::format("--out {}: {}", folder.string(), why));
}

// Every regular file under `root`, as paths relative to it; hidden folders (a verdict's
// scratch) are not outputs.
std::set<std::string> files_under(const fs::path& root) {
    std::set<std::string> files;
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
        if (it->is_directory() && it->path().filename().string().front() == '.') {
            it.disable_recursion_pending();
            continue;
        }
        if (it->is_regular_file()) files.insert(it->path().lexically_relative(root).string());  // no system calls
    }
    return files;
}

bool hidden(const fs::path& p) { return p.filename().string().front() == '.'; }

// The first component of an output's name (relative to its folder): its folder there, or itself.
std::string top_of(const std::string& name) { return name.substr(0, name.find('/')); }

// Whether every file under `dir` (hidden ones too; symbolic links are not followed) is one of
// `outputs`, named relative to `root`, and nothing there is hidden: a folder that may go
// whole, or be replaced whole.
bool holds_only(const fs::path& root, const fs::path& dir, const std::set<std::string>& outputs) {
    std::error_code error;
    for (auto it = fs::recursive_directory_iterator(dir, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error)) {
        const fs::file_type type = it->symlink_status(error).type();
        if (hidden(it->path()) || (type != fs::file_type::directory &&
                                   (type != fs::file_type::regular || !outputs.count(it->path().lexically_relative(root).string()))))
            return false;
    }
    return !error;
}

}  // namespace

OutputFolder::OutputFolder(const fs::path& folder) : folder_(folder) {
    std::error_code error;
    fs::create_directories(folder_, error);
    if (error || !fs::is_directory(folder_)) refuse(folder_, "cannot create the folder: " + (error ? error.message() : "a file is in the way"));
    const fs::path lock = folder_ / kLock;
    lock_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_ < 0) refuse(folder_, fmt::format("cannot create {} ({})", lock.string(), std::strerror(errno)));
    if (::flock(lock_, LOCK_EX | LOCK_NB) != 0) {
        std::string pid;
        std::getline(std::ifstream(lock), pid);
        ::close(lock_);
        refuse(folder_, fmt::format("another surfvp run (pid {}) is writing there; wait for it or give another --out",
                                    pid.empty() ? "?" : pid));
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(lock_, 0) != 0 || ::pwrite(lock_, pid.data(), pid.size(), 0) != ssize_t(pid.size()))
        refuse(folder_, fmt::format("cannot write {} ({})", lock.string(), std::strerror(errno)));
    // Holding the lock, any staging folder here is a killed run's.
    for (const auto& entry : fs::directory_iterator(folder_, error))
        if (entry.path().filename().string().rfind(kStagingPrefix, 0) == 0) fs::remove_all(entry.path(), error);
    staging_ = folder_ / (kStagingPrefix + std::to_string(::getpid()));
    fs::create_directories(staging_, error);
    if (error) refuse(folder_, "cannot create " + staging_.string() + ": " + error.message());
}

OutputFolder::~OutputFolder() {
    std::error_code ignored;
    if (!published_) fs::remove_all(staging_, ignored);
    ::close(lock_);  // releases the lock
}

std::set<std::string> OutputFolder::previous_outputs() const {
    std::set<std::string> previous;
    std::ifstream manifest(folder_ / kManifest);
    if (manifest) {
        for (std::string line; std::getline(manifest, line);)
            if (!line.empty()) previous.insert(line);
        return previous;
    }
    std::error_code error;
    for (const std::string& name : kKnownOutputs)
        if (fs::exists(folder_ / name, error)) previous.insert(name);
    if (fs::is_directory(folder_ / "keypoints", error))
        for (const std::string& f : files_under(folder_ / "keypoints")) previous.insert("keypoints/" + f);
    return previous;
}

void OutputFolder::publish() {
    const std::set<std::string> written = files_under(staging_), previous = previous_outputs();
    const std::set<std::string> whole = move_folders(written, previous);
    auto in_whole = [&whole](const std::string& f) { return whole.count(top_of(f)) > 0; };
    std::error_code error;
    for (const std::string& f : written) {
        if (in_whole(f)) continue;
        const fs::path to = folder_ / f;
        if (fs::path(f).extension() == ".gtkw") name_published_files(staging_ / f);
        fs::create_directories(to.parent_path(), error);
        if (!error) fs::rename(staging_ / f, to, error);
        if (error) refuse(folder_, fmt::format("cannot move {} into place: {}", f, error.message()));
    }
    for (const std::string& f : previous) {
        if (written.count(f) || in_whole(f)) continue;  // a folder replaced whole took its previous files along
        fs::remove(folder_ / f, error);
        const fs::path parent = (folder_ / f).parent_path();
        if (parent != folder_ && fs::is_empty(parent, error)) fs::remove(parent, error);
    }
    std::string manifest;
    for (const std::string& f : written) manifest += f + "\n";
    write_file_atomically(folder_ / kManifest, manifest);
    fs::remove_all(staging_, error);  // with the folders replaced whole, the previous run's files in them
    published_ = true;
}

// A folder of outputs (keypoints/: two files a frame) goes into place in one step when the
// folder it replaces holds only the previous run's outputs, or there is none: renamed, or
// exchanged with the previous one (which then leaves with the staging folder). Its files then
// change at once, and none is renamed over another, which on ext4 writes the new file's data
// out first (~0.2 ms a file here, 40 files a 20-frame run). The rest go file by file.
std::set<std::string> OutputFolder::move_folders(const std::set<std::string>& written,
                                                 const std::set<std::string>& previous) const {
    std::set<std::string> folders;  // the staging folder's, before any leaves it
    for (const std::string& f : written)
        if (f.find('/') != std::string::npos) folders.insert(top_of(f));
    for (const std::string& f : written)
        if (fs::path(f).extension() == ".gtkw") folders.erase(top_of(f));  // rewritten as they go
    std::set<std::string> whole;
    std::error_code error;
    for (const std::string& name : folders) {
        const fs::path from = staging_ / name, to = folder_ / name;
        if (!holds_only(staging_, from, written)) continue;
        const fs::file_type there = fs::symlink_status(to, error).type();
        bool moved = false;
        if (there == fs::file_type::not_found)
            moved = ::rename(from.c_str(), to.c_str()) == 0;
        else if (there == fs::file_type::directory && holds_only(folder_, to, previous))
            moved = ::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_EXCHANGE) == 0;  // not on every file system
        if (moved) whole.insert(name);
    }
    return whole;
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
