// The SequenceGenerator's schedules replayed by the checker, against their lower bounds.
#include <cstdio>
#include <gtest/gtest.h>

#include "models/fhg/sequence_generator.h"

namespace surfvp::fhg {
namespace {

struct Mode {
    BusWord word;
    bool reuse;
    const char* name;
};

class Schedules : public testing::TestWithParam<Mode> {};

TEST_P(Schedules, DeliverExactlyTheNeededReadsAndRespectBusyTripleMacs) {
    SequenceParams p;
    p.bus_word = GetParam().word;
    p.reuse = GetParam().reuse;
    const Sequence s = generate_sequence(p);
    EXPECT_EQ(check_sequence(s, p), "");
    EXPECT_EQ(s.reads_per_block, 18 * 32);
    EXPECT_GE(s.cycles, s.optimal_cycles);
    EXPECT_GE(s.optimal_cycles, 48) << "each TripleMAC adds 8 x1 reads of Dxy... 48 cycles of work";
    std::printf("%s: %d cycles/block, bound %d, overhead %.1f %%, %d words, %d distinct reads\n", GetParam().name,
                s.cycles, s.optimal_cycles, 100 * s.overhead(), s.words_delivered, s.distinct_reads_per_block);
}

INSTANTIATE_TEST_SUITE_P(BusWordsAndReuse, Schedules,
                         testing::Values(Mode{BusWord::quad, true, "quad_reuse"}, Mode{BusWord::quad, false, "quad"},
                                         Mode{BusWord::scalar, true, "scalar_reuse"},
                                         Mode{BusWord::scalar, false, "scalar"}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SequenceGenerator, BoundsFollowTheStructure) {
    SequenceParams p;
    p.bus_word = BusWord::scalar;
    p.reuse = false;
    EXPECT_EQ(generate_sequence(p).optimal_cycles, 144);  // 576 reads / 4 buses
    p.bus_word = BusWord::quad;
    EXPECT_EQ(generate_sequence(p).optimal_cycles, 48);  // 192 quad words / 4 buses = 48 = TripleMAC work
    p.read_buses = 2;
    EXPECT_EQ(generate_sequence(p).optimal_cycles, 96);
}

TEST(SequenceGenerator, MoreBusesNeverSlower) {
    SequenceParams p;
    p.bus_word = BusWord::scalar;
    int previous = 1 << 30;
    for (unsigned buses : {1u, 2u, 4u, 6u, 8u}) {
        p.read_buses = buses;
        const Sequence s = generate_sequence(p);
        EXPECT_EQ(check_sequence(s, p), "") << buses;
        EXPECT_LE(s.cycles, previous) << buses << " buses";
        previous = s.cycles;
    }
}

TEST(SequenceGenerator, CheckerCatchesABrokenSequence) {
    SequenceParams p;
    Sequence s = generate_sequence(p);
    Sequence dropped = s;
    dropped.steps.pop_back();
    EXPECT_NE(check_sequence(dropped, p).find("does not receive exactly its reads"), std::string::npos);
    // Hand a x3 TripleMAC a second value in the next cycle.
    for (size_t i = 0; i < s.steps.size(); ++i)
        for (const Tap& t : s.steps[i].taps)
            if (std::abs(t.coefficient) == 3) {
                Sequence busy = s;
                busy.steps.push_back({s.steps[i].cycle + 1, 0, 0, 0, {{t.triple_mac, 0, 1, Response::xy}}});
                const std::string why = check_sequence(busy, p);
                EXPECT_TRUE(why.find("busy") != std::string::npos || why.find("two") != std::string::npos) << why;
                return;
            }
    FAIL() << "no x3 tap found";
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
}

}  // namespace
}  // namespace surfvp::fhg
