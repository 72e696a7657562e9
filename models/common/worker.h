#pragma once
// One background thread that runs a model's plain C++ work (never SystemC) while the kernel
// simulates something else. Jobs run one at a time in the order submitted; submit() returns at
// once with the job's number (0, 1, ...), wait(n) blocks until jobs 0..n are done and rethrows
// what one threw, drain() waits for all. The caller keeps a job's inputs unchanged until it is
// done and reads its outputs only after waiting for it.
//
// The kernel's thread submits a job per FHG block row (thousands a run) and is the simulator's
// limit, so waking a sleeping thread (a futex call and an inter-processor wake-up, ~15 us on a
// virtual machine) is what this class avoids: either side spins a short while for the other
// before it sleeps (`spin`: tens of microseconds cover the kernel's thread between two block
// rows; zero for a worker that is rarely busy), and a side wakes the other only when it says
// it sleeps.
#include <atomic>
#include <chrono>
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
    explicit Worker(std::chrono::microseconds spin = std::chrono::microseconds(200));
    ~Worker();  // finishes the jobs already submitted
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;

    size_t submit(std::function<void()> job);
    void wait(size_t job);
    void drain();

private:
    void loop();
    template <class Ready>
    bool spin_until(Ready ready) const;
    bool next_job(std::function<void()>& job);  // false: stopping with nothing left

    const std::chrono::microseconds spin_;
    std::mutex mutex_;
    std::condition_variable work_;  // the worker sleeps on it
    std::condition_variable done_;  // waiters sleep on it
    std::deque<std::function<void()>> jobs_;
    size_t submitted_ = 0;               // under mutex_
    std::atomic<size_t> queued_{0};      // = submitted_, read by the spinning worker
    std::atomic<size_t> finished_{0};    // jobs done, read by spinning waiters
    bool worker_sleeps_ = false;         // under mutex_
    int waiters_sleeping_ = 0;           // under mutex_
    bool stopping_ = false;
    std::exception_ptr failure_;
    std::thread thread_;  // last: started once the rest exists
};

}  // namespace surfvp
