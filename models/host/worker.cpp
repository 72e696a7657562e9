#include "models/host/worker.h"

#include <algorithm>
#include <utility>

namespace surfvp {

Worker::Worker(std::chrono::microseconds spin, Waiter waiter)
    : spin_(spin), waiter_(waiter), thread_([this] { loop(); }) {}

Worker::~Worker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    work_.notify_one();
    thread_.join();
}

template <class Ready>
bool Worker::spin_until(Ready ready) const {
    if (spin_.count() <= 0) return ready();
    const auto until = std::chrono::steady_clock::now() + spin_;
    for (int polls = 0;; ++polls) {
        if (ready()) return true;
        if (polls % 64 == 63 && std::chrono::steady_clock::now() > until) return false;
        Worker::relax();
    }
}

size_t Worker::submit(std::function<void()> job) {
    bool wake = false;
    size_t number = 0;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        number = submitted_.load(std::memory_order_relaxed);
        jobs_.push_back({number, std::move(job)});
        submitted_.store(number + 1, std::memory_order_release);
        wake = worker_sleeps_;
        worker_sleeps_ = false;
    }
    if (wake) work_.notify_one();  // outside the lock: the woken thread does not block on it
    return number;
}

void Worker::wait(size_t job) {
    const auto reached = [&] { return finished_.load(std::memory_order_acquire) > job; };
    const size_t last = waiter_ == Waiter::runs_any ? ~size_t(0) : job;
    for (Job mine; !reached() && take_up_to(last, mine);) run(mine);
    // What is left of jobs 0..job runs on the worker; nothing the waiter could take.
    if (!reached() && !spin_until(reached)) {
        std::unique_lock<std::mutex> lock(mutex_);
        ++waiters_sleeping_;
        done_.wait(lock, reached);
        --waiters_sleeping_;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

void Worker::drain() {
    const size_t submitted = submitted_.load(std::memory_order_relaxed);  // the caller is the submitter
    if (submitted) wait(submitted - 1);
}

bool Worker::take_up_to(size_t last, Job& job) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (jobs_.empty() || jobs_.front().number > last) return false;
    job = std::move(jobs_.front());
    jobs_.pop_front();
    taken_.fetch_add(1, std::memory_order_relaxed);
    return true;
}

// A job first; else background work when there may be some; else sleeps until either comes.
Worker::Next Worker::next(Job& job) {
    const auto poked = [&] { return pokes_.load(std::memory_order_acquire) != pokes_seen_; };
    spin_until(
        [&] { return submitted_.load(std::memory_order_acquire) > taken_.load(std::memory_order_relaxed) || poked(); });
    std::unique_lock<std::mutex> lock(mutex_);
    while (jobs_.empty() && !poked() && !stopping_) {
        worker_sleeps_ = true;
        work_.wait(lock);
    }
    if (jobs_.empty()) return stopping_ ? Next::stop : Next::background;
    job = std::move(jobs_.front());
    jobs_.pop_front();
    taken_.fetch_add(1, std::memory_order_relaxed);
    return Next::job;
}

bool Worker::background_piece() {
    const uint64_t pokes = pokes_.load(std::memory_order_acquire);
    bool did = false;
    {
        std::lock_guard<std::mutex> lock(background_mutex_);
        did = background_ && background_();
    }
    if (!did) pokes_seen_ = pokes;  // nothing to do as of those pokes: wait for the next one
    return did;
}

void Worker::set_background(std::function<bool()> work) {
    std::lock_guard<std::mutex> lock(background_mutex_);
    background_ = std::move(work);
}

void Worker::poke() {
    pokes_.fetch_add(1, std::memory_order_release);
    bool wake = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        wake = worker_sleeps_;
        worker_sleeps_ = false;
    }
    if (wake) work_.notify_one();
}

void Worker::run(Job& job) {
    std::exception_ptr thrown;
    try {
        job.run();
    } catch (...) {
        thrown = std::current_exception();
    }
    job.run = nullptr;  // its captures go before the job counts as done
    bool wake = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (thrown && (!failure_ || job.number < failed_job_)) {
            failure_ = thrown;
            failed_job_ = job.number;
        }
        size_t finished = finished_.load(std::memory_order_relaxed);
        if (job.number != finished) {
            done_ahead_.push_back(job.number);
        } else {
            for (++finished;; ++finished) {  // and those done ahead that now follow on
                const auto next = std::find(done_ahead_.begin(), done_ahead_.end(), finished);
                if (next == done_ahead_.end()) break;
                done_ahead_.erase(next);
            }
            finished_.store(finished, std::memory_order_release);
        }
        wake = waiters_sleeping_ > 0;
    }
    if (wake) done_.notify_all();
}

void Worker::loop() {
    for (Job job;;) {
        const Next n = next(job);
        if (n == Next::stop) return;
        if (n == Next::job)
            run(job);
        else
            background_piece();
    }
}

}  // namespace surfvp
