#include "models/common/worker.h"

#include <utility>

namespace surfvp {

Worker::Worker() : thread_([this] { loop(); }) {}

Worker::~Worker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

size_t Worker::submit(std::function<void()> job) {
    std::lock_guard<std::mutex> lock(mutex_);
    jobs_.push_back(std::move(job));
    changed_.notify_all();
    return submitted_++;
}

void Worker::wait(size_t job) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return done_ > job; });
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

void Worker::drain() {
    size_t submitted = 0;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        submitted = submitted_;
    }
    if (submitted) wait(submitted - 1);
}

void Worker::loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        changed_.wait(lock, [this] { return !jobs_.empty() || stopping_; });
        if (jobs_.empty()) return;  // stopping with nothing left
        std::function<void()> job = std::move(jobs_.front());
        jobs_.pop_front();
        lock.unlock();
        try {
            job();
        } catch (...) {
            lock.lock();
            if (!failure_) failure_ = std::current_exception();
            lock.unlock();
        }
        lock.lock();
        ++done_;
        changed_.notify_all();
    }
}

}  // namespace surfvp
