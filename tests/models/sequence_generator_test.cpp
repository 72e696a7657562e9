// The SequenceGenerator's schedules replayed by the checker, against their lower bounds and
// the line FIFO's port limits.
#include <cstdio>
#include <gtest/gtest.h>
#include <map>

#include "models/fhg/sequence_cache.h"

namespace surfvp::fhg {
namespace {

struct Mode {
    BusWord word;
    bool reuse;
    unsigned ports;
    const char* name;
};

class Schedules : public testing::TestWithParam<Mode> {};

TEST_P(Schedules, BothSchedulersDeliverExactlyTheReadsWithinEveryLimit) {
    SequenceParams p;
    p.bus_word = GetParam().word;
    p.reuse = GetParam().reuse;
    p.line_ports = GetParam().ports;
    for (Scheduler scheduler : {Scheduler::basic, Scheduler::improved}) {
        p.scheduler = scheduler;
        const Sequence s = generate_sequence(p);
        EXPECT_EQ(check_sequence(s, p), "") << scheduler_name(scheduler);
        EXPECT_EQ(s.reads_per_block, 18 * 32);
        EXPECT_GE(s.interval, s.optimal_cycles);
        EXPECT_GE(s.optimal_cycles, 48) << "each TripleMAC has 48 cycles of additions";
        EXPECT_GE(s.span, s.interval - 1);
        std::printf("%s %s: %d cycles/block (span %d), bound %d (%s), overhead %.1f %%, %d words\n", GetParam().name,
                    scheduler_name(scheduler), s.interval, s.span, s.optimal_cycles, s.optimal_limit.c_str(),
                    100 * s.overhead(), s.words_delivered);
    }
}

INSTANTIATE_TEST_SUITE_P(BusWordsReuseAndPorts, Schedules,
                         testing::Values(Mode{BusWord::quad, true, 2, "quad_reuse"}, Mode{BusWord::quad, false, 2, "quad"},
                                         Mode{BusWord::quad, true, 4, "quad_4_ports"},
                                         Mode{BusWord::pair, true, 2, "pair_reuse"},
                                         Mode{BusWord::scalar, true, 2, "scalar_reuse"},
                                         Mode{BusWord::scalar, false, 2, "scalar"}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SequenceGenerator, ImprovedIsNeverWorseThanBasic) {
    for (unsigned ports : {2u, 4u}) {
        SequenceParams p;
        p.line_ports = ports;
        const int basic = generate_sequence(p).interval;
        p.scheduler = Scheduler::improved;
        EXPECT_LE(generate_sequence(p).interval, basic) << ports << " ports";
    }
}

TEST(SequenceGenerator, BoundsFollowTheStructure) {
    SequenceParams p;
    p.bus_word = BusWord::scalar;
    p.reuse = false;
    Sequence s = generate_sequence(p);
    EXPECT_EQ(s.optimal_cycles, 144);  // 576 reads / 4 buses
    EXPECT_EQ(s.optimal_limit, "read buses");
    p.bus_word = BusWord::quad;
    s = generate_sequence(p);
    // 192 quad words / 4 buses = 48 = TripleMAC work; and line 0 carries 48 quads' 96 reads
    // over 2 ports (every filter's Dxy reads the rows -1 / 0 and 0 / 1 around the centre).
    EXPECT_EQ(s.optimal_cycles, 48);
    EXPECT_EQ(s.optimal_limit, "TripleMAC work, read buses, line FIFO ports (line 0)");
    p.read_buses = 2;
    EXPECT_EQ(generate_sequence(p).optimal_cycles, 96);
    p.read_buses = 4;
    p.line_ports = 1;
    p.line_banks = 2;  // a quad takes one read of each bank of each line: line 0 at 1 port per BRAM
    EXPECT_EQ(generate_sequence(p).optimal_cycles, 48);
}

// One read port per line makes the centre line the limit; more ports relax it.
TEST(SequenceGenerator, FewerLinePortsNeverFaster) {
    SequenceParams p;
    p.bus_word = BusWord::pair;
    p.reuse = false;
    int previous = 0;
    for (unsigned ports : {4u, 2u}) {
        p.line_ports = ports;
        const Sequence s = generate_sequence(p);
        EXPECT_EQ(check_sequence(s, p), "") << ports;
        EXPECT_GE(s.interval, previous) << ports << " ports";
        previous = s.interval;
    }
    p.line_ports = 1;
    p.line_banks = 1;
    EXPECT_THROW(generate_sequence(p), std::invalid_argument);  // a pair reads 2 values of one BRAM
}

TEST(SequenceGenerator, MoreBusesNeverSlower) {
    SequenceParams p;
    p.bus_word = BusWord::scalar;
    p.scheduler = Scheduler::improved;
    int previous = 1 << 30;
    for (unsigned buses : {1u, 2u, 4u, 6u, 8u}) {
        p.read_buses = buses;
        const Sequence s = generate_sequence(p);
        EXPECT_EQ(check_sequence(s, p), "") << buses;
        EXPECT_LE(s.interval, previous) << buses << " buses";
        previous = s.interval;
    }
}

// The basic script is the median of its passes, so it lies within their spread.
TEST(SequenceGenerator, BasicIsTheMedianPass) {
    SequenceParams p;
    const Sequence s = generate_sequence(p);
    EXPECT_LE(s.spread[0], s.interval);
    EXPECT_GE(s.spread[1], s.interval);
    EXPECT_LT(s.spread[0], s.spread[1]) << "tie-breaks change a single pass's length";
}

// The next block's sequence starts right after this one's last word: a x3 still being added
// overlaps it, and the interval is shorter than the span only by that tail.
TEST(SequenceGenerator, SuccessiveBlocksOverlapTheLastAdditions) {
    SequenceParams p;
    p.scheduler = Scheduler::improved;
    const Sequence s = generate_sequence(p);
    int last_word = 0;
    for (const Step& step : s.steps) last_word = std::max(last_word, step.cycle);
    EXPECT_GE(s.interval, last_word + 1);
    EXPECT_LE(s.span - s.interval, int(p.x3_cycles) - 1);
}

TEST(SequenceGenerator, CheckerCatchesEveryBrokenLimit) {
    SequenceParams p;
    const Sequence s = generate_sequence(p);
    ASSERT_EQ(check_sequence(s, p), "");
    Sequence dropped = s;
    dropped.steps.pop_back();
    EXPECT_NE(check_sequence(dropped, p).find("does not receive exactly its reads"), std::string::npos);

    // Hand a x3 TripleMAC a second value in the next cycle.
    bool found = false;
    for (size_t i = 0; i < s.steps.size() && !found; ++i)
        for (const Tap& t : s.steps[i].taps)
            if (std::abs(t.coefficient) == 3 && s.steps[i].cycle + 1 < s.interval) {
                Sequence busy = s;
                busy.steps.push_back({s.steps[i].cycle + 1, 0, 0, 0, {{t.triple_mac, 0, 1, Response::xy}}});
                const std::string why = check_sequence(busy, p);
                EXPECT_TRUE(why.find("busy") != std::string::npos || why.find("two") != std::string::npos) << why;
                found = true;
                break;
            }
    EXPECT_TRUE(found) << "no x3 tap found";

    // Two words of the same cycle on line 0: more reads than its two ports.
    Sequence crowded = s;
    crowded.steps.erase(std::remove_if(crowded.steps.begin(), crowded.steps.end(), [](const Step& st) { return st.cycle == 0; }),
                        crowded.steps.end());
    crowded.steps.push_back({0, 1, -1, 0, {}});
    crowded.steps.push_back({0, 2, 5, 0, {}});
    EXPECT_NE(check_sequence(crowded, p).find("serves more than 2 reads"), std::string::npos) << check_sequence(crowded, p);

    // A word outside the 52 x 52 window.
    Sequence outside = s;
    outside.steps.front().y = 25;  // a quad at line 25 would need line 26
    EXPECT_NE(check_sequence(outside, p).find("window"), std::string::npos) << check_sequence(outside, p);

    // The next block starting before a TripleMAC has finished its last x3.
    Sequence early = s;
    early.interval = s.span - int(p.x3_cycles);
    EXPECT_FALSE(check_sequence(early, p).empty());
}

// Without reuse every word is one group's delivery; a word that also feeds another size's
// TripleMAC is refused.
TEST(SequenceGenerator, CheckerHoldsAMachineWithoutReuseToWholeGroups) {
    SequenceParams p;
    p.reuse = false;
    Sequence s = generate_sequence(p);
    ASSERT_EQ(check_sequence(s, p), "");
    Step& first = s.steps.front();
    const int other = first.taps.front().triple_mac < 4 ? 16 : 0;  // a TripleMAC of another size
    first.taps.push_back({other, 0, 1, Response::xy});
    EXPECT_NE(check_sequence(s, p).find("without reuse"), std::string::npos) << check_sequence(s, p);
    p.reuse = true;
    EXPECT_EQ(check_sequence(s, p).find("without reuse"), std::string::npos);
}

TEST(SequenceGenerator, ImpossibleConfigurationsAreNamed) {
    auto message = [](SequenceParams p) {
        try {
            generate_sequence(p);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    SequenceParams p;
    p.triple_macs = 12;
    EXPECT_NE(message(p).find("fhg.triple_macs"), std::string::npos);
    p = SequenceParams{};
    p.fifo_lines = 40;
    EXPECT_NE(message(p).find("52-line window"), std::string::npos) << message(p);
    p = SequenceParams{};
    p.read_buses = 0;
    EXPECT_NE(message(p).find("fhg.read_buses"), std::string::npos);
    p = SequenceParams{};
    p.line_ports = 1;
    EXPECT_NE(message(p).find("fhg.line_ports"), std::string::npos) << message(p);
    p = SequenceParams{};
    p.line_banks = 4;
    EXPECT_NE(message(p).find("fhg.line_banks"), std::string::npos) << message(p);
}

TEST(SequenceGenerator, CacheGivesTheSameSequence) {
    SequenceParams p;
    const Sequence& a = cached_sequence(p);
    const Sequence& b = cached_sequence(p);
    EXPECT_EQ(&a, &b);
    EXPECT_EQ(a.interval, generate_sequence(p).interval);
}

}  // namespace
}  // namespace surfvp::fhg
