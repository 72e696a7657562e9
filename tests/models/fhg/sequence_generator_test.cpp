// The SequenceGenerator's schedules replayed by the checker, against their lower bounds and
// the line FIFO's port limits.
#include <algorithm>
#include <cstdio>
#include <gtest/gtest.h>
#include <map>
#include <tuple>

#include "models/fhg/sequence_cache.h"

namespace surfvp::fhg {
namespace {

struct Mode {
    BusWord word;
    bool reuse;
    LineFifo fifo;
    const char* name;
};

class Schedules : public testing::TestWithParam<Mode> {};

TEST_P(Schedules, BothSchedulersDeliverExactlyTheReadsWithinEveryLimit) {
    SequenceParams p;
    p.bus_word = GetParam().word;
    p.reuse = GetParam().reuse;
    p.line_fifo = GetParam().fifo;
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
                         testing::Values(Mode{BusWord::quad, true, LineFifo::tdp, "quad_reuse"},
                                         Mode{BusWord::quad, false, LineFifo::tdp, "quad"},
                                         Mode{BusWord::quad, false, LineFifo::tdp_x2, "quad_x2"},
                                         Mode{BusWord::quad, true, LineFifo::tdp_x2, "quad_reuse_x2"},
                                         Mode{BusWord::quad, false, LineFifo::banked, "quad_banked"},
                                         Mode{BusWord::pair, true, LineFifo::tdp, "pair_reuse"},
                                         Mode{BusWord::scalar, true, LineFifo::tdp, "scalar_reuse"},
                                         Mode{BusWord::scalar, false, LineFifo::tdp, "scalar"},
                                         Mode{BusWord::scalar, false, LineFifo::sdp72, "scalar_sdp72"}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SequenceGenerator, ImprovedIsNeverWorseThanBasic) {
    for (LineFifo fifo : {LineFifo::tdp, LineFifo::tdp_x2, LineFifo::banked}) {
        SequenceParams p;
        p.line_fifo = fifo;
        const int basic = generate_sequence(p).interval;
        p.scheduler = Scheduler::improved;
        EXPECT_LE(generate_sequence(p).interval, basic) << line_fifo_name(fifo);
    }
}

TEST(SequenceGenerator, BoundsFollowTheStructure) {
    SequenceParams p;
    p.line_groups = 1;  // every lane reaches every line
    p.bus_word = BusWord::scalar;
    p.reuse = false;
    Sequence s = generate_sequence(p);
    EXPECT_EQ(s.optimal_cycles, 144);  // 576 reads / 4 buses
    EXPECT_EQ(s.optimal_limit, "read buses");
    p.bus_word = BusWord::quad;
    p.line_fifo = LineFifo::tdp;
    s = generate_sequence(p);
    // 192 quad words / 4 buses = 48 = TripleMAC work. Line 0, the busiest, is read by every
    // filter's Dxy (rows -1 / 0 and 0 / 1 around the centre), but octave 2's words read one
    // value each, so its reads stay under 2 ports x 48 cycles.
    EXPECT_EQ(s.optimal_cycles, 48);
    EXPECT_EQ(s.optimal_limit, "TripleMAC work, read buses");
    p.line_fifo = LineFifo::tdp_x2;
    EXPECT_EQ(generate_sequence(p).optimal_limit, "TripleMAC work, read buses");
    p.read_buses = 2;
    EXPECT_EQ(generate_sequence(p).optimal_cycles, 96);
    p.read_buses = 4;
    p.line_fifo = LineFifo::banked;  // a quad takes one read of each bank of each line
    EXPECT_EQ(generate_sequence(p).optimal_cycles, 48);
}

// The paper's note 4: the optimal state is the buses carrying a word every cycle, so the basic
// script's overhead counts idle bus cycles only, against the words it carries.
TEST(SequenceGenerator, IdleBusOverheadCountsTheWordsCarried) {
    for (LineFifo fifo : {LineFifo::tdp, LineFifo::tdp_x2}) {
        SequenceParams p;
        p.line_fifo = fifo;
        p.reuse = false;
        const Sequence s = generate_sequence(p);
        EXPECT_EQ(s.words_delivered, 192);  // 16 octave-1 quads x 32 reads / 4 pixels + 2 x 32 octave-2 words
        EXPECT_EQ(s.busy_bus_cycles, 48);
        EXPECT_DOUBLE_EQ(s.idle_bus_overhead(), s.interval / 48.0 - 1);
    }
}

// An octave-2 word carries one value: it reads that value's line once, through the port its
// lane is wired to (`tdp`: the lane's column). Another bus wanting that value shares the read;
// one wanting another value of the line through the same port must wait for another cycle.
TEST(SequenceGenerator, AWordReadsOnlyTheValuesItsTapsTake) {
    SequenceParams p;
    p.line_groups = 1;  // every lane reaches every line
    p.reuse = false;
    p.line_fifo = LineFifo::tdp;
    const Sequence s = generate_sequence(p);
    const auto single =
        std::find_if(s.steps.begin(), s.steps.end(), [](const Step& st) { return st.taps.size() == 1; });
    ASSERT_NE(single, s.steps.end()) << "the basic script delivers octave 2's values one a word";
    SequenceParams shared = p;
    shared.reuse = true;  // three TripleMACs take from words like it: only the ports can object
    Sequence cycle;
    cycle.interval = s.interval;
    for (int bus = 0; bus < 3; ++bus) {
        Step copy = *single;
        copy.bus = bus;
        copy.taps[0].triple_mac = bus;
        if (bus == 2) copy.x += copy.x > 0 ? -2 : 2;  // the same lane, so the same port: another column
        cycle.steps.push_back(copy);
        const std::string why = check_sequence(cycle, shared);
        EXPECT_EQ(why.find("reads two addresses") != std::string::npos, bus == 2) << bus << ": " << why;
    }
    EXPECT_EQ(lane_port(p, 0, single->taps[0].lane), lane_port(p, 2, single->taps[0].lane));
}

// Fewer reads a line makes the centre line the limit; more relax it.
TEST(SequenceGenerator, FewerLineReadsNeverFaster) {
    SequenceParams p;
    p.bus_word = BusWord::pair;
    p.reuse = false;
    int previous = 0;
    for (LineFifo fifo : {LineFifo::tdp_x2, LineFifo::tdp}) {
        p.line_fifo = fifo;
        const Sequence s = generate_sequence(p);
        EXPECT_EQ(check_sequence(s, p), "") << line_fifo_name(fifo);
        EXPECT_GE(s.interval, previous) << line_fifo_name(fifo);
        previous = s.interval;
    }
    p.line_fifo = LineFifo::sdp72;
    EXPECT_THROW(generate_sequence(p), std::invalid_argument);  // a pair at an odd column straddles two 72-bit words
}

// The basic script as the paper's chip ran it: about 11 % over note 4's optimal state once a
// line serves four reads a cycle; 25 % with two (docs/sources.md#fhg, measured by seqgen).
TEST(SequenceGenerator, BasicScriptOverheadByLineFifo) {
    SequenceParams p;
    p.reuse = false;
    p.line_groups = 1;
    p.line_fifo = LineFifo::tdp_x2;
    const Sequence four = generate_sequence(p);
    EXPECT_EQ(four.interval, 53);
    EXPECT_NEAR(four.idle_bus_overhead(), 0.104, 0.001);
    p.line_fifo = LineFifo::banked;
    EXPECT_EQ(generate_sequence(p).interval, 53);
    p.line_fifo = LineFifo::tdp;
    EXPECT_GT(generate_sequence(p).interval, 53);
}

// A bus that reaches half of the lines (the default) costs the basic script nothing: octave
// 2's single values sit in whichever line of their quad word the bus reaches. A quarter costs
// five cycles: octave 1's words crowd the groups of the lines around the centre.
TEST(SequenceGenerator, LineGroupsConstrainWhichBusCarriesAWord) {
    SequenceParams p;
    p.reuse = false;
    for (const auto& [groups, interval, bound] : {std::tuple{1u, 53, 48}, {2u, 53, 48}, {4u, 58, 48}}) {
        p.line_groups = groups;
        const Sequence s = generate_sequence(p);
        EXPECT_EQ(check_sequence(s, p), "") << groups;
        EXPECT_EQ(s.interval, interval) << groups << " groups";
        EXPECT_EQ(s.optimal_cycles, bound) << groups << " groups";
        for (const Step& step : s.steps) ASSERT_TRUE(bus_reaches(p, step.bus, step.y)) << groups;
    }
    // Scalar words cannot move: the busiest group's words over its bus bound the script.
    p.bus_word = BusWord::scalar;
    p.line_groups = 4;
    EXPECT_GT(generate_sequence(p).optimal_cycles, 144) << "576 words over 4 buses, unevenly over the groups";
    p.bus_word = BusWord::quad;
    // The checker refuses a word on a bus of another group.
    p.line_groups = 2;
    Sequence s = generate_sequence(p);
    Step& moved = s.steps.back();
    moved.bus ^= 1;
    s.steps.erase(std::remove_if(s.steps.begin(), s.steps.end() - 1,
                                 [&](const Step& st) { return st.cycle == moved.cycle && st.bus == moved.bus; }),
                  s.steps.end() - 1);
    EXPECT_NE(check_sequence(s, p).find("reaches line group"), std::string::npos) << check_sequence(s, p);
    // Groups the buses or the FIFO cannot be dealt into are refused, naming the parameter.
    p.line_groups = 3;
    EXPECT_THROW(generate_sequence(p), std::invalid_argument);
    p.line_groups = 4;
    p.read_buses = 6;
    try {
        generate_sequence(p);
        ADD_FAILURE() << "6 buses in 4 groups";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("fhg.line_groups"), std::string::npos) << e.what();
    }
}

TEST(SequenceGenerator, MoreBusesNeverSlower) {
    SequenceParams p;
    p.line_groups = 1;  // every lane reaches every line
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
    p.line_groups = 1;            // every lane reaches every line
    p.line_fifo = LineFifo::tdp;  // two reads a line and cycle
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

    // Two quads of the same cycle on line 0, each taken whole: each lane's port asked for two
    // addresses.
    Sequence crowded = s;
    crowded.steps.erase(
        std::remove_if(crowded.steps.begin(), crowded.steps.end(), [](const Step& st) { return st.cycle == 0; }),
        crowded.steps.end());
    auto whole_quad = [](int first_tm) {
        std::vector<Tap> taps;
        for (int lane = 0; lane < 4; ++lane) taps.push_back({first_tm + lane, lane, 1, Response::xy});
        return taps;
    };
    crowded.steps.push_back({0, 1, -1, 0, whole_quad(0)});
    crowded.steps.push_back({0, 2, 5, 0, whole_quad(4)});
    EXPECT_NE(check_sequence(crowded, p).find("line 0 (BRAM 0) port 0 reads two addresses in cycle 0"),
              std::string::npos)
        << check_sequence(crowded, p);

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
    p.line_fifo = LineFifo::sdp72;  // a quad at an odd column needs two 72-bit reads of a line
    EXPECT_NE(message(p).find("fhg.line_fifo: sdp72 serves 1 aligned pair"), std::string::npos) << message(p);
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
