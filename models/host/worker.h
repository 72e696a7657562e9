#pragma once
// One background thread that runs a model's plain C++ work (never SystemC) while the kernel
// simulates something else. Jobs are independent of each other; they start in the order
// submitted. submit() returns at once with the job's number (0, 1, ...); wait(n) returns once
// jobs 0..n are done and rethrows what one threw (the lowest-numbered); drain() waits for all.
// A waiter does not idle while jobs it waits for are still queued: it takes them off the queue
// and runs them itself, so that both cores work on a backlog. With Waiter::runs_any, while the
// worker still runs one of those, the waiter also takes the ones after (jobs are independent)
// and returns at most one job's time after its own is done: for a caller with nothing else to
// do (direct mode), not for one whose time is the simulation's limit (the kernel's thread,
// which the worker keeps up with). The caller keeps a job's inputs unchanged until it is done
// and reads its outputs only after waiting for it. One thread submits and waits.
//
// The kernel's thread submits a job per FHG block row (thousands a run) and is the simulator's
// limit, so waking a sleeping thread (a futex call and an inter-processor wake-up, ~15 us on a
// virtual machine) is what this class avoids: either side spins a short while for the other
// before it sleeps (`spin`: tens of microseconds cover the kernel's thread between two block
// rows; zero for a worker that is rarely busy), and a side wakes the other only when it says
// it sleeps.
//
// Besides its jobs, the worker can be given background work for its idle time (the software
// stage describing a task's candidates ahead): a function that does one small piece and says
// whether it did anything. Jobs come first: the worker takes a piece only when no job is
// queued, and a job submitted meanwhile waits for at most one piece.
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
    enum class Waiter { runs_its_jobs, runs_any };
    explicit Worker(std::chrono::microseconds spin = std::chrono::microseconds(200),
                    Waiter waiter = Waiter::runs_its_jobs);
    ~Worker();  // finishes the jobs already submitted
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;

    size_t submit(std::function<void()> job);
    void wait(size_t job);
    void drain();

    // The background work (nullptr: none). It runs on the worker's thread only, never throws,
    // and returns false when it has nothing to do; the worker then calls it again only after
    // poke(). Returns once a piece in progress is done, so the old work is not running after it.
    void set_background(std::function<bool()> work);
    // There may be background work again: the worker calls it when idle, waking up if it sleeps.
    void poke();

    // A spinning thread's pause: it stays on its core without a system call.
    static void relax() {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#else
        std::this_thread::yield();
#endif
    }

private:
    struct Job {
        size_t number = 0;
        std::function<void()> run;
    };
    void loop();
    enum class Next { job, background, stop };
    Next next(Job& job);                     // the worker's next thing to do; waits for one
    bool background_piece();                 // one piece of background work; false: there was none
    bool take_up_to(size_t last, Job& job);  // a waiter's: the queue's first if numbered <= last
    void run(Job& job);                      // runs it, records its failure, counts it done
    template <class Ready>
    bool spin_until(Ready ready) const;

    const std::chrono::microseconds spin_;
    const Waiter waiter_;
    std::mutex mutex_;
    std::condition_variable work_;  // the worker sleeps on it
    std::condition_variable done_;  // waiters sleep on it
    std::deque<Job> jobs_;
    std::atomic<size_t> submitted_{0};  // written by the submitting thread, under mutex_
    std::atomic<size_t> taken_{0};      // jobs taken off the queue, by the worker or a waiter
    std::atomic<size_t> finished_{0};   // every job below it is done; read by spinning waiters
    std::vector<size_t> done_ahead_;    // done above finished_ (two ran at once); under mutex_
    bool worker_sleeps_ = false;        // under mutex_
    std::mutex background_mutex_;       // held while a piece runs, and to replace the work
    std::function<bool()> background_;  // under background_mutex_
    std::atomic<uint64_t> pokes_{0};    // poke() calls; the worker has looked for work after pokes_seen_
    uint64_t pokes_seen_ = 0;           // the worker's own
    int waiters_sleeping_ = 0;          // under mutex_
    bool stopping_ = false;
    size_t failed_job_ = 0;
    std::exception_ptr failure_;  // the lowest-numbered job's that threw
    std::thread thread_;          // last: started once the rest exists
};

}  // namespace surfvp
