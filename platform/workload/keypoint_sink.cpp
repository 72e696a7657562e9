#include "platform/workload/keypoint_sink.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>

#include "sw/eval/keypoint_file.h"

namespace surfvp {
namespace fs = std::filesystem;

fs::path keypoint_file(const fs::path& folder, size_t frame) {
    return folder / "keypoints" / fmt::format("frame_{:04}.surf", frame);
}

void KeypointSink::use_thread(bool threaded) {
    finish();
    writer_ = threaded ? std::make_unique<Worker>(std::chrono::microseconds(0)) : nullptr;
}

void KeypointSink::write(size_t frame, const surf::Keypoints& keypoints) {
    if (out_.empty() || failure_) return;
    try {
        if (written_.empty()) fs::create_directories(fs::path(out_) / "keypoints");
        const fs::path file = keypoint_file(out_, frame);
        written_.push_back(file.lexically_relative(out_).string());
        if (!writer_) return eval::write_keypoint_file(file, keypoints);
        last_write_ = writer_->submit([this, file, keypoints] {
            try {
                eval::write_keypoint_file(file, keypoints);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(mutex_);
                if (!writer_failure_) writer_failure_ = std::current_exception();
            }
        });
    } catch (...) {
        failure_ = std::current_exception();
    }
}

void KeypointSink::finish() {
    if (writer_ && last_write_) writer_->wait(*last_write_);
    last_write_.reset();
    const std::lock_guard<std::mutex> lock(mutex_);
    if (writer_failure_ && !failure_) failure_ = writer_failure_;
}

std::vector<std::string> KeypointSink::files_written() {
    finish();
    if (failure_) std::rethrow_exception(failure_);
    std::vector<std::string> names = written_;
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace surfvp
