#pragma once
// One background thread that runs a model's plain C++ work (never SystemC) while the kernel
// simulates something else. Jobs are independent of each other; they start in the order
// submitted. submit() returns at once with the job's number (0, 1, ...); wait(n) returns once
// jobs 0..n are done and rethrows what one threw (the lowest-numbered); drain() waits for all.
// A waiter does not idle while jobs it waits for are still queued: it takes them off the queue
// and runs them itself, so that both cores work on a backlog. The caller keeps a job's inputs
// unchanged until it is done and reads its outputs only after waiting for it. One thread
// submits and waits.
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
#include <vector>

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
    struct Job {
        size_t number = 0;
        std::function<void()> run;
    };
    void loop();
    bool next_job(Job& job);             // the worker's next; false: stopping with nothing left
    bool take_up_to(size_t last, Job& job);  // a waiter's: the queue's first if numbered <= last
    void run(Job& job);                  // runs it, records its failure, counts it done
    template <class Ready>
    bool spin_until(Ready ready) const;

    const std::chrono::microseconds spin_;
    std::mutex mutex_;
    std::condition_variable work_;  // the worker sleeps on it
    std::condition_variable done_;  // waiters sleep on it
    std::deque<Job> jobs_;
    std::atomic<size_t> submitted_{0};   // written by the submitting thread, under mutex_
    std::atomic<size_t> taken_{0};       // jobs taken off the queue, by the worker or a waiter
    std::atomic<size_t> finished_{0};    // every job below it is done; read by spinning waiters
    std::vector<size_t> done_ahead_;     // done above finished_ (two ran at once); under mutex_
    bool worker_sleeps_ = false;         // under mutex_
    int waiters_sleeping_ = 0;           // under mutex_
    bool stopping_ = false;
    size_t failed_job_ = 0;
    std::exception_ptr failure_;         // the lowest-numbered job's that threw
    std::thread thread_;  // last: started once the rest exists
};

}  // namespace surfvp
