// The background worker: jobs in submission order, wait(n) covers jobs 0..n, a job's exception
// reaches the waiter, and no hand-over is lost whether the other side spins or sleeps.
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "models/common/worker.h"

namespace surfvp {
namespace {

TEST(Worker, RunsJobsInOrderAndWaitCoversEveryEarlierJob) {
    std::vector<int> order;
    Worker w;
    for (int i = 0; i < 1000; ++i) EXPECT_EQ(w.submit([&order, i] { order.push_back(i); }), size_t(i));
    w.wait(499);
    EXPECT_GE(order.size(), 500u);
    for (size_t i = 0; i < 500; ++i) EXPECT_EQ(order[i], int(i));
    w.drain();
    ASSERT_EQ(order.size(), 1000u);
    for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], int(i));
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

TEST(Worker, AJobsExceptionReachesTheWaiterAndLaterJobsStillRun) {
    Worker w;
    bool later = false;
    const size_t bad = w.submit([] { throw std::runtime_error("row 7 failed"); });
    w.submit([&later] { later = true; });
    try {
        w.wait(bad);
        FAIL() << "wait() returned without the job's exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "row 7 failed");
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

}  // namespace
}  // namespace surfvp
