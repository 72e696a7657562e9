#pragma once
// A run's keypoint files (keypoints/frame_NNNN.surf in its folder), written as the frames are
// reported: on the caller's thread, or on a thread of the files' own once one is asked for.
// Their system calls block (creating a file alone took ~0.1 ms on ext4 here, two files a
// frame), which on a shared worker held up the block rows queued behind them. A write that
// fails (a full disk) is kept for files_written() to throw after the run, and no further file
// is tried.
#include <cstddef>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "models/host/worker.h"
#include "sw/surf/surf.h"

namespace surfvp {

// A frame's keypoint file in a run folder: keypoints/frame_NNNN.surf.
std::filesystem::path keypoint_file(const std::filesystem::path& folder, size_t frame);

class KeypointSink {
public:
    // Files go under `dir` from now on; "" (the default): none are written.
    void write_into(const std::string& dir) { out_ = dir; }
    // The files handed out so far are finished; with `threaded`, later ones are written on a
    // thread of their own.
    void use_thread(bool threaded);
    void write(size_t frame, const surf::Keypoints& keypoints);
    // After the run: the names written, relative to the folder, sorted (frames are reported in
    // the order they finish). Throws the first write that failed.
    std::vector<std::string> files_written();

private:
    void finish();  // waits for the thread's files and takes their failure

    std::string out_;
    std::vector<std::string> written_;  // relative to out_
    std::exception_ptr failure_;        // the first that failed; no more are handed out after it
    std::unique_ptr<Worker> writer_;
    std::optional<size_t> last_write_;  // the writer's job number of the last file handed to it
    std::mutex mutex_;
    std::exception_ptr writer_failure_;  // a file the writer failed to write; under mutex_
};

}  // namespace surfvp
