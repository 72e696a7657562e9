// The L1 data-cache model against hand-computed cases (PPC440: 32 KB, 32-byte lines,
// 64 ways, so 16 sets and a set index from address bits 5..8).
#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <stdexcept>
#include <vector>

#include "sw/cpu_cost/cache_model.h"

namespace surfvp::sw {
namespace {

CacheParams ppc440(Replacement replacement = Replacement::lru) {
    CacheParams p;
    p.replacement = replacement;
    return p;
}

// Reads one word in each line of [begin, end).
CacheModel::Result scan(CacheModel& cache, uint32_t begin, uint32_t end) {
    CacheModel::Result total;
    for (uint32_t a = begin; a < end; a += 32) {
        const CacheModel::Result r = cache.access(a, 4);
        total.hits += r.hits;
        total.misses += r.misses;
    }
    return total;
}

TEST(CacheModel, Ppc440GeometryHas16Sets) {
    EXPECT_EQ(CacheModel(ppc440()).sets(), 16u);  // 32768 / (32 x 64)
}

TEST(CacheModel, SequentialScanOfTwiceTheSizeMissesEverywhereOnTheSecondPass) {
    for (Replacement r : {Replacement::lru, Replacement::round_robin}) {
        CacheModel cache(ppc440(r));
        const CacheModel::Result first = scan(cache, 0, 64 * 1024);
        const CacheModel::Result second = scan(cache, 0, 64 * 1024);
        EXPECT_EQ(first.misses, 2048u);  // 64 KiB / 32 B: every line new
        // Each set sees 128 lines in turn; the one wanted next was evicted 64 fills ago.
        EXPECT_EQ(second.misses, 2048u);
        EXPECT_EQ(second.hits, 0u);
        EXPECT_EQ(cache.misses(), 4096u);
    }
}

TEST(CacheModel, WorkingSetThatFitsHitsOnTheSecondPass) {
    for (uint32_t bytes : {16u * 1024, 32u * 1024}) {
        CacheModel cache(ppc440());
        EXPECT_EQ(scan(cache, 0x100000, 0x100000 + bytes).misses, bytes / 32);
        const CacheModel::Result again = scan(cache, 0x100000, 0x100000 + bytes);
        EXPECT_EQ(again.hits, bytes / 32);
        EXPECT_EQ(again.misses, 0u);
    }
}

TEST(CacheModel, WordsOfOneLineMissOnceThenHit) {
    CacheModel cache(ppc440());
    for (uint32_t a = 64; a < 96; a += 4) cache.access(a, 4);
    EXPECT_EQ(cache.misses(), 1u);
    EXPECT_EQ(cache.hits(), 7u);
    EXPECT_DOUBLE_EQ(cache.hit_rate(), 7.0 / 8.0);
}

TEST(CacheModel, AnAccessCrossingALineTouchesBoth) {
    CacheModel cache(ppc440());
    CacheModel::Result r = cache.access(30, 4);  // bytes 30..33: lines 0 and 1
    EXPECT_EQ(r.misses, 2u);
    r = cache.access(28, 8);  // bytes 28..35: the same two lines
    EXPECT_EQ(r.hits, 2u);
    EXPECT_EQ(r.misses, 0u);
    EXPECT_EQ(cache.access(0, 0).misses + cache.access(0, 0).hits, 0u);  // zero bytes: nothing
}

// Lines 512 bytes apart (16 sets x 32 bytes) all fall into one set: 64 of them fit, 65 do
// not, however much of the rest of the cache is free.
TEST(CacheModel, AssociativityConflictInOneSet) {
    CacheModel cache(ppc440());
    for (int pass = 0; pass < 2; ++pass)
        for (uint32_t i = 0; i < 64; ++i) cache.access(i * 512, 4);
    EXPECT_EQ(cache.misses(), 64u);
    EXPECT_EQ(cache.hits(), 64u);

    CacheModel conflict(ppc440());
    for (int pass = 0; pass < 3; ++pass)
        for (uint32_t i = 0; i < 65; ++i) conflict.access(i * 512, 4);
    EXPECT_EQ(conflict.misses(), 3u * 65);  // LRU cycling through ways + 1: never a hit
    EXPECT_EQ(conflict.hits(), 0u);
    // The other 15 sets are untouched: a line of set 1 still misses once, then hits.
    EXPECT_EQ(conflict.access(32, 4).misses, 1u);
    EXPECT_EQ(conflict.access(32, 4).hits, 1u);
}

// A 2-way, 4-set cache by hand: lines 0, 128, 256 (bytes) all map to set 0.
//   access   LRU (ways: most recent first)        round-robin (way 0, way 1; victim)
//   0        miss [0]                              miss [0, -] v1
//   128      miss [128, 0]                         miss [0, 128] v0
//   0        hit  [0, 128]                         hit
//   256      miss [256, 0]   (evicts 128)          miss [256, 128] v1 (evicts 0)
//   128      miss [128, 256] (evicts 0)            hit
//   0        miss [0, 128]   (evicts 256)          miss [256, 0] v0 (evicts 128)
TEST(CacheModel, SmallCacheLruAgainstRoundRobinByHand) {
    const uint32_t sequence[] = {0, 128, 0, 256, 128, 0};
    const bool lru_hit[] = {false, false, true, false, false, false};
    const bool rr_hit[] = {false, false, true, false, true, false};
    CacheParams p{256, 32, 2, Replacement::lru};
    CacheModel lru(p);
    p.replacement = Replacement::round_robin;
    CacheModel rr(p);
    ASSERT_EQ(lru.sets(), 4u);
    for (size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(lru.access(sequence[i], 4).hits, lru_hit[i] ? 1u : 0u) << "LRU access " << i;
        EXPECT_EQ(rr.access(sequence[i], 4).hits, rr_hit[i] ? 1u : 0u) << "round-robin access " << i;
    }
}

// The PPC440's round-robin replaces the oldest fill even if it was just used; LRU keeps it.
TEST(CacheModel, FullSetReuseSeparatesLruFromRoundRobin) {
    for (Replacement r : {Replacement::lru, Replacement::round_robin}) {
        CacheModel cache(ppc440(r));
        for (uint32_t i = 0; i < 64; ++i) cache.access(i * 512, 4);  // set 0 full, line 0 filled first
        cache.access(0, 4);                                          // line 0 used again
        cache.access(64 * 512, 4);                                   // a 65th line needs a victim
        const bool kept = cache.access(0, 4).hits == 1;
        EXPECT_EQ(kept, r == Replacement::lru);
    }
}

TEST(CacheModel, InvalidateDropsEveryLine) {
    CacheModel cache(ppc440());
    scan(cache, 0, 1024);
    cache.invalidate();
    EXPECT_EQ(scan(cache, 0, 1024).misses, 32u);
}

TEST(CacheModel, RefusesGeometryItCannotIndex) {
    EXPECT_THROW(CacheModel(CacheParams{32768, 24, 64, Replacement::lru}), std::invalid_argument);     // line
    EXPECT_THROW(CacheModel(CacheParams{3 * 2048, 32, 64, Replacement::lru}), std::invalid_argument);  // 3 sets
    EXPECT_THROW(CacheModel(CacheParams{1000, 32, 4, Replacement::lru}), std::invalid_argument);       // not whole sets
    EXPECT_THROW(CacheModel(CacheParams{32768, 32, 0, Replacement::lru}), std::invalid_argument);
}

TEST(CacheModel, SameAccessesSameCounts) {
    auto run = [] {
        CacheModel cache(ppc440());
        uint32_t a = 12345;
        for (int i = 0; i < 100000; ++i) {
            a = a * 1103515245u + 12345u;
            cache.access((a >> 8) % (256 * 1024), 4);
        }
        return std::make_pair(cache.hits(), cache.misses());
    };
    EXPECT_EQ(run(), run());
}

// The two replacements by their definitions: per set, its lines in order, the next to go
// last. LRU: a hit moves its line to the front, a miss puts the line there. Round-robin: a
// hit changes nothing, a miss puts the line at the front (so the one filled first goes).
// Either way a full set drops its last line on a miss.
class Reference {
public:
    Reference(uint32_t sets, uint32_t ways, Replacement replacement)
        : sets_(sets), ways_(ways), replacement_(replacement), order_(sets) {}
    bool touch(uint32_t line) {
        std::deque<uint32_t>& set = order_[line % sets_];
        const auto it = std::find(set.begin(), set.end(), line);
        if (it != set.end()) {
            if (replacement_ == Replacement::lru) {
                set.erase(it);
                set.push_front(line);
            }
            return true;
        }
        if (set.size() == ways_) set.pop_back();
        set.push_front(line);
        return false;
    }
    void invalidate() {
        for (auto& set : order_) set.clear();
    }

private:
    uint32_t sets_, ways_;
    Replacement replacement_;
    std::vector<std::deque<uint32_t>> order_;
};

// The Haar wavelets' kind of traffic: many rows of an image 4 KB wide (so that the rows share
// sets and sets overflow), each touch checked against the definition, with invalidates.
void expect_the_definition_touch_by_touch(const CacheParams& p) {
    CacheModel cache(p);
    Reference reference(cache.sets(), p.ways, p.replacement);
    uint32_t seed = 7;
    uint64_t hits = 0;
    for (int i = 0; i < 200000; ++i) {
        seed = seed * 1103515245u + 12345u;
        if (i % 50000 == 49999) {
            cache.invalidate();
            reference.invalidate();
        }
        const uint32_t row = (seed >> 8) % 96, column = (seed >> 20) % 160;  // a 96 x 160-pixel window
        const uint32_t address = 0x100000 + row * 4096 + column * 4;
        const bool hit = cache.access(address, 4).hits == 1;
        ASSERT_EQ(hit, reference.touch(address / 32)) << "touch " << i << ", " << p.ways << " ways";
        hits += hit;
    }
    EXPECT_GT(hits, 10000u);  // both hits and misses were exercised
    EXPECT_LT(hits, 190000u);
}

TEST(CacheModel, LruHitsAndMissesEqualTheDefinitionTouchByTouch) {
    for (const uint32_t ways : {64u, 4u, 1u}) {
        CacheParams p = ppc440();
        p.ways = ways;
        expect_the_definition_touch_by_touch(p);
    }
}

TEST(CacheModel, RoundRobinHitsAndMissesEqualTheDefinitionTouchByTouch) {
    for (const uint32_t ways : {64u, 4u}) {
        CacheParams p = ppc440(Replacement::round_robin);
        p.ways = ways;
        expect_the_definition_touch_by_touch(p);
    }
}

// Lines anywhere in the 32-bit space: the last line below 4 GiB, line 0, and a read that
// ends at the top. The look-up table is made in chunks as lines are first touched.
TEST(CacheModel, LinesAtBothEndsOfTheAddressSpace) {
    CacheModel cache(ppc440());
    EXPECT_EQ(cache.access(0xFFFFFFE0u, 32).misses, 1u);
    EXPECT_EQ(cache.access(0x00000000u, 4).misses, 1u);
    EXPECT_EQ(cache.access(0xFFFFFFFCu, 4).hits, 1u);
    EXPECT_EQ(cache.access(0x0000001Cu, 4).hits, 1u);
    const CacheModel::Result both = cache.access(0xFFFFFFC0u, 64);  // the line below, then the top one
    EXPECT_EQ(both.misses, 1u);
    EXPECT_EQ(both.hits, 1u);
}

}  // namespace
}  // namespace surfvp::sw
