// The DRAM's busy intervals: first come first served in time order, gaps kept for work
// handed over out of order.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace surfvp
