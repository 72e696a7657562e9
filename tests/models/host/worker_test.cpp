// The background worker: wait(n) covers jobs 0..n, a waiter runs the queued jobs it waits for
// (and, if it runs any, the next ones while the worker runs one of those), the lowest-numbered
// job's exception reaches the waiter, and no hand-over is lost whether the other side spins or
// sleeps; background work runs in the idle time, after the jobs, until it says it has nothing,
// again after each poke, and never after it is taken back.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "models/host/worker.h"

namespace surfvp {
namespace {

TEST(Worker, WaitCoversEveryEarlierJob) {
    std::vector<int> out(1000, -1);
    Worker w;
    for (int i = 0; i < 1000; ++i) EXPECT_EQ(w.submit([&out, i] { out[size_t(i)] = i * i; }), size_t(i));
    w.wait(499);
    for (size_t i = 0; i < 500; ++i) ASSERT_EQ(out[i], int(i * i)) << i;
    w.drain();
    for (size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], int(i * i)) << i;
}

// Job 0 as the first job submitted: it holds the worker until `released` (at most 5 s) and
// notes whether it saw that; made once the worker has taken it.
struct HoldingJob {
    explicit HoldingJob(Worker& w) {
        w.submit([this] {
            ran_on = std::this_thread::get_id();
            started = true;
            const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
            while (!released && std::chrono::steady_clock::now() < until) std::this_thread::yield();
            saw_release = released.load();
        });
        while (!started) std::this_thread::yield();
    }
    std::atomic<bool> started{false}, released{false}, saw_release{false};
    std::thread::id ran_on;
};

// While the worker is held up by job 0, a waiter for job 3 runs jobs 1 to 3 itself: job 0
// sees job 3 done (it would wait in vain if only the worker ran jobs).
TEST(Worker, AWaiterRunsTheQueuedJobsItWaitsFor) {
    Worker w;
    HoldingJob first(w);
    std::vector<std::thread::id> ran_on(4);
    for (size_t k = 1; k <= 3; ++k)
        w.submit([&, k] {
            ran_on[k] = std::this_thread::get_id();
            if (k == 3) first.released = true;
        });
    w.wait(3);
    EXPECT_TRUE(first.saw_release);
    for (size_t k = 1; k <= 3; ++k) EXPECT_EQ(ran_on[k], std::this_thread::get_id()) << "job " << k;
    EXPECT_NE(first.ran_on, std::this_thread::get_id());
}

// Waiter::runs_any: while the worker runs job 0, a waiter for job 0 runs job 1 itself (jobs
// are independent): job 0 sees job 1 done (it would wait in vain if the waiter only spun).
TEST(Worker, WhileTheWorkerRunsTheJobWaitedForAWaiterThatRunsAnyRunsTheNextQueuedOne) {
    Worker w(std::chrono::microseconds(200), Worker::Waiter::runs_any);
    HoldingJob first(w);
    std::thread::id second_ran_on;
    w.submit([&] {
        second_ran_on = std::this_thread::get_id();
        first.released = true;
    });
    w.wait(0);
    EXPECT_TRUE(first.saw_release);
    EXPECT_EQ(second_ran_on, std::this_thread::get_id());
    EXPECT_NE(first.ran_on, std::this_thread::get_id());
}

// Pauses longer than the spin let both sides fall asleep: each job must still be picked up
// and each waiter woken.
TEST(Worker, HandsOverAcrossSleepsOnBothSides) {
    Worker w;
    int done = 0;
    for (int i = 0; i < 5; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(3));  // the worker is asleep
        const size_t job = w.submit([&done] {
            std::this_thread::sleep_for(std::chrono::milliseconds(3));  // the waiter falls asleep
            ++done;
        });
        w.wait(job);
        EXPECT_EQ(done, i + 1);
    }
}

// Job 1 throws first in time (job 0 takes longer), yet the waiter gets job 0's: the same
// error whichever thread ran what.
TEST(Worker, TheLowestNumberedJobsExceptionReachesTheWaiterAndLaterJobsStillRun) {
    Worker w;
    std::atomic<bool> later{false};
    w.submit([] {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        throw std::runtime_error("row 0 failed");
    });
    const size_t second = w.submit([] { throw std::runtime_error("row 1 failed"); });
    w.submit([&later] { later = true; });
    try {
        w.wait(second);
        FAIL() << "wait() returned without the job's exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "row 0 failed");
    }
    w.drain();
    EXPECT_TRUE(later);
}

TEST(Worker, DestroyingItFinishesTheJobsSubmitted) {
    int done = 0;
    {
        Worker w;
        for (int i = 0; i < 50; ++i) w.submit([&done] { ++done; });
    }
    EXPECT_EQ(done, 50);
}

// Pieces run on the worker's thread until the work says it has none; a poke (here to a
// sleeping worker) brings it back; once taken back, it is never called again.
TEST(Worker, BackgroundWorkRunsUntilItHasNoneAndAgainAfterAPoke) {
    Worker w;
    std::atomic<int> left{5}, pieces{0}, calls{0};
    std::atomic<bool> on_worker{true};
    const auto caller = std::this_thread::get_id();
    w.set_background([&] {
        ++calls;
        if (std::this_thread::get_id() == caller) on_worker = false;
        if (left <= 0) return false;
        --left;
        ++pieces;
        return true;
    });
    auto settle = [&] {
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
        for (int seen = -1; calls != seen && std::chrono::steady_clock::now() < until;) {
            seen = calls;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));  // longer than the spin: it sleeps
        }
    };
    w.poke();
    settle();
    EXPECT_EQ(pieces, 5);
    const int after_first = calls;
    EXPECT_EQ(after_first, 6);  // five pieces and the call that found none; no poke, no call
    left = 3;
    w.poke();
    settle();
    EXPECT_EQ(pieces, 8);
    EXPECT_TRUE(on_worker);
    w.set_background(nullptr);
    const int before = calls;
    left = 100;
    w.poke();
    settle();
    EXPECT_EQ(calls, before);
}

// With background work that never runs out, a submitted job is still taken by the worker
// (the submitter does not wait(), which would run it itself).
TEST(Worker, JobsComeBeforeBackgroundWork) {
    Worker w;
    std::atomic<uint64_t> pieces{0};
    w.set_background([&] {
        ++pieces;
        return true;
    });
    w.poke();
    while (pieces < 100) std::this_thread::yield();
    std::atomic<bool> ran{false};
    std::thread::id ran_on;
    w.submit([&] {
        ran_on = std::this_thread::get_id();
        ran = true;
    });
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (!ran && std::chrono::steady_clock::now() < until) std::this_thread::yield();
    EXPECT_TRUE(ran);
    w.drain();
    EXPECT_NE(ran_on, std::this_thread::get_id());
    w.set_background(nullptr);
}

}  // namespace
}  // namespace surfvp
