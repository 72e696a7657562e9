// The DRAM's busy intervals: first come first served in time order, gaps kept for work
// handed over out of order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "models/memory/busy_timeline.h"

namespace surfvp {
namespace {

TEST(BusyTimeline, InTimeOrderItIsFirstComeFirstServed) {
    BusyTimeline t;
    EXPECT_EQ(t.reserve(0, 100), 0u);
    EXPECT_EQ(t.reserve(50, 100), 100u);  // waits for the first
    EXPECT_EQ(t.reserve(150, 10), 200u);  // and for the second
    EXPECT_EQ(t.reserve(500, 10), 500u);  // free again
    EXPECT_EQ(t.intervals(), 2u);         // [0, 210) merged, [500, 510)
}

TEST(BusyTimeline, WorkHandedOverLateUsesAGapThatFits) {
    BusyTimeline t;
    t.reserve(1000, 100);                   // [1000, 1100)
    EXPECT_EQ(t.reserve(0, 100), 0u);       // fits before
    EXPECT_EQ(t.reserve(950, 100), 1100u);  // would overlap: after it
    EXPECT_EQ(t.reserve(850, 100), 850u);   // [850, 950) fits exactly
    EXPECT_EQ(t.reserve(900, 10), 950u);    // the gap [950, 1000)
    EXPECT_EQ(t.reserve(900, 60), 1200u);   // too small for 60: after the rest
}

TEST(BusyTimeline, ForgettingThePastKeepsTheFuture) {
    BusyTimeline t;
    t.reserve(0, 100);
    t.reserve(300, 100);
    t.forget_before(200);
    EXPECT_EQ(t.intervals(), 1u);
    EXPECT_EQ(t.reserve(350, 10), 400u);
    EXPECT_EQ(t.reserve(0, 0), 0u);  // nothing to place
}

// The definition: the earliest start at or after the request (the request itself or the end
// of a reserved interval) where the work overlaps nothing reserved.
struct Reference {
    struct Span {
        uint64_t start, end;
    };
    std::vector<Span> reserved;

    uint64_t reserve(uint64_t request, uint64_t length) {
        std::vector<uint64_t> candidates{request};
        for (const Span& s : reserved)
            if (s.end > request) candidates.push_back(s.end);
        std::sort(candidates.begin(), candidates.end());
        for (uint64_t c : candidates)
            if (std::none_of(reserved.begin(), reserved.end(),
                             [&](const Span& s) { return c < s.end && s.start < c + length; })) {
                reserved.push_back({c, c + length});
                return c;
            }
        return 0;
    }
};

// Requests mostly in time order with some handed over early, the past forgotten as simulated
// time advances.
TEST(BusyTimeline, EveryStartIsTheEarliestThatFits) {
    Reference reference;
    BusyTimeline t;
    std::mt19937 random(7);
    uint64_t now = 0;
    for (int i = 0; i < 2000; ++i) {
        now += random() % 40;
        if (i % 50 == 0) t.forget_before(now);
        const uint64_t request = now + (random() % 8 == 0 ? random() % 2000 : random() % 30);
        const uint64_t length = 1 + random() % 60;
        ASSERT_EQ(t.reserve(request, length), reference.reserve(request, length)) << "reservation " << i;
    }
}

// The DRAM's own pattern: the CPU hands over a batch of short fills far ahead of time (hundreds
// of intervals at the back), while the DMA masters' bursts arrive at the kernel's time and go in
// near the front (insert() then moves the few intervals before them, not the many after).
TEST(BusyTimeline, BurstsAtTheKernelsTimeGoBeforeTheFillsAhead) {
    Reference reference;
    BusyTimeline t;
    std::mt19937 random(11);
    uint64_t now = 0;
    for (int batch = 0; batch < 6; ++batch) {
        uint64_t at = now + 50;
        for (int fill = 0; fill < 300; ++fill, at += 20 + random() % 40)
            ASSERT_EQ(t.reserve(at, 10), reference.reserve(at, 10)) << "batch " << batch << " fill " << fill;
        for (int burst = 0; burst < 200; ++burst) {
            now += random() % 60;
            t.forget_before(now);
            const uint64_t length = 5 + random() % 20;
            ASSERT_EQ(t.reserve(now, length), reference.reserve(now, length))
                << "batch " << batch << " burst " << burst;
        }
    }
    EXPECT_GT(t.intervals(), 100u);  // the fills still ahead
}

}  // namespace
}  // namespace surfvp
