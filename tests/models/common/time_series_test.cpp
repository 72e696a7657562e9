// Figures per time bin: busy shares and highest levels, and a long run's bins merged by twos
// so a series never holds more than TimeSeries::kMaxBins.
#include <gtest/gtest.h>

#include "models/common/time_series.h"

namespace surfvp {
namespace {

constexpr uint64_t kMs = 1'000'000'000;

TEST(TimeSeries, BusyTimeIsSharedOutOverTheBinsItCovers) {
    TimeSeries s(kMs);
    s.busy(kMs / 2, 2 * kMs);  // half of bin 0, all of bin 1
    EXPECT_EQ(s.values(), (std::vector<double>{0.5, 1.0}));
}

TEST(TimeSeries, LevelsCarryForwardAndKeepTheHighestInABin) {
    TimeSeries s(kMs);
    s.level(kMs / 4, 3);
    s.level(kMs / 2, 1);
    s.level(3 * kMs + 1, 2);
    EXPECT_EQ(s.values(), (std::vector<double>{3, 1, 1, 2}));
}

TEST(TimeSeries, ALongRunMergesBinsByTwosAndKeepsTheBusyTime) {
    TimeSeries s(kMs);
    s.busy(0, kMs);              // bin 0 all busy
    s.busy(kMs, kMs + kMs / 2);  // bin 1 half busy
    EXPECT_EQ(s.values().size(), 2u);
    const uint64_t end = TimeSeries::kMaxBins * kMs;  // the first time past kMaxBins bins of 1 ms
    s.busy(end, end + kMs);
    EXPECT_EQ(s.bin_ps(), 2 * kMs);
    const std::vector<double> v = s.values();
    EXPECT_EQ(v.size(), TimeSeries::kMaxBins / 2 + 1);
    EXPECT_DOUBLE_EQ(v[0], 0.75);     // 1.5 ms busy in a 2 ms bin
    EXPECT_DOUBLE_EQ(v.back(), 0.5);  // 1 ms of the last 2 ms bin
    // Ten times longer still: the width doubles until the run fits again.
    s.busy(10 * end, 10 * end + kMs);
    EXPECT_EQ(s.bin_ps(), 16 * kMs);
    EXPECT_LE(s.values().size(), TimeSeries::kMaxBins);
    EXPECT_NEAR(s.values()[0], 1.5 / 16, 1e-4);  // values are given to four decimals
}

TEST(TimeSeries, MergedLevelsKeepTheHigherOfTwoBins) {
    TimeSeries s(kMs);
    s.level(0, 5);
    s.level(kMs, 7);
    s.level(2 * kMs, 1);
    s.level(TimeSeries::kMaxBins * kMs, 4);
    EXPECT_EQ(s.bin_ps(), 2 * kMs);
    const std::vector<double> v = s.values();
    EXPECT_EQ(v[0], 7);  // max(5, 7)
    EXPECT_EQ(v[1], 7);  // bin 2 began at 7 before the level fell to 1
    EXPECT_EQ(v[2], 1);  // carried forward
    EXPECT_EQ(v.back(), 4);
}

}  // namespace
}  // namespace surfvp
