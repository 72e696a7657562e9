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
    EXPECT_EQ(t.reserve(50, 100), 100u);   // waits for the first
    EXPECT_EQ(t.reserve(150, 10), 200u);   // and for the second
    EXPECT_EQ(t.reserve(500, 10), 500u);   // free again
    EXPECT_EQ(t.intervals(), 2u);          // [0, 210) merged, [500, 510)
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

// Against the definition: the earliest start at or after the request (the request itself or
// the end of a reserved interval) where the work overlaps nothing reserved; requests mostly in
// time order with some handed over early, the past forgotten as simulated time advances.
TEST(BusyTimeline, EveryStartIsTheEarliestThatFits) {
    struct Span {
        uint64_t start, end;
    };
    std::vector<Span> reserved;
    auto earliest = [&](uint64_t request, uint64_t length) {
        std::vector<uint64_t> candidates{request};
        for (const Span& s : reserved)
            if (s.end > request) candidates.push_back(s.end);
        std::sort(candidates.begin(), candidates.end());
        for (uint64_t c : candidates)
            if (std::none_of(reserved.begin(), reserved.end(), [&](const Span& s) { return c < s.end && s.start < c + length; }))
                return c;
        return uint64_t(0);
    };
    BusyTimeline t;
    std::mt19937 random(7);
    uint64_t now = 0;
    for (int i = 0; i < 2000; ++i) {
        now += random() % 40;
        if (i % 50 == 0) t.forget_before(now);
        const uint64_t request = now + (random() % 8 == 0 ? random() % 2000 : random() % 30);
        const uint64_t length = 1 + random() % 60;
        const uint64_t want = earliest(request, length);
        ASSERT_EQ(t.reserve(request, length), want) << "reservation " << i;
        reserved.push_back({want, want + length});
    }
}

}  // namespace
}  // namespace surfvp
