#pragma once
// One background thread that runs a model's plain C++ work (never SystemC) while the kernel
// simulates something else. Jobs run one at a time in the order submitted; submit() returns at
// once with the job's number (0, 1, ...), wait(n) blocks until jobs 0..n are done and rethrows
// what one threw, drain() waits for all. The caller keeps a job's inputs unchanged until it is
// done and reads its outputs only after waiting for it.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace surfvp {

class Worker {
public:
    Worker();
    ~Worker();  // finishes the jobs already submitted
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;

    size_t submit(std::function<void()> job);
    void wait(size_t job);
    void drain();

private:
    void loop();

    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<std::function<void()>> jobs_;
    size_t submitted_ = 0, done_ = 0;
    bool stopping_ = false;
    std::exception_ptr failure_;
    std::thread thread_;  // last: started once the rest exists
};

}  // namespace surfvp
