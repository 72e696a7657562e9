// The sequence memory image: its layout, the round trip through both file formats back to a
// sequence the replay checker accepts, and the refusal of words the encoder cannot write.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <utility>

#include "fhg/bus_swap.h"
#include "models/fhg/sequence_cache.h"
#include "models/fhg/sequence_memory.h"

namespace surfvp::fhg {
namespace {

struct Configuration {
    const char* name;
    unsigned read_buses;
    BusWord word;
    LineFifo fifo;
    bool reuse;
};

// The steps as comparable tuples, taps sorted by TripleMAC.
std::vector<std::tuple<int, int, int, int, std::vector<std::tuple<int, int, int, int>>>> normal(const Sequence& s) {
    std::vector<std::tuple<int, int, int, int, std::vector<std::tuple<int, int, int, int>>>> out;
    for (const Step& step : s.steps) {
        std::vector<std::tuple<int, int, int, int>> taps;
        for (const Tap& t : step.taps) taps.emplace_back(t.triple_mac, t.lane, t.coefficient, int(t.response));
        std::sort(taps.begin(), taps.end());
        out.emplace_back(step.cycle, step.bus, step.x, step.y, taps);
    }
    std::sort(out.begin(), out.end());
    return out;
}

class RoundTrip : public testing::TestWithParam<Configuration> {};

// Both schedulers at the default and two other machines: encoded, written as COE and as
// $readmemh, read back and decoded, the steps are the generator's and the checker accepts them.
TEST_P(RoundTrip, BothFormatsGiveBackTheSequenceTheCheckerAccepts) {
    SequenceParams p;
    p.read_buses = GetParam().read_buses;
    p.bus_word = GetParam().word;
    p.line_fifo = GetParam().fifo;
    p.reuse = GetParam().reuse;
    for (Scheduler scheduler : {Scheduler::basic, Scheduler::improved}) {
        p.scheduler = scheduler;
        const Sequence& s = cached_sequence(p);
        const SequenceImage image = encode_sequence(s, p);
        ASSERT_EQ(int(image.words.size()), s.interval);
        for (const std::string& text : {to_coe(image, "test"), to_readmemh(image, "test")}) {
            const SequenceImage read = parse_image(text, sequence_layout(p));
            ASSERT_EQ(read.words, image.words) << scheduler_name(scheduler);
            const Sequence back = decode_sequence(read, p);
            EXPECT_EQ(back.interval, s.interval);
            EXPECT_EQ(normal(back), normal(s)) << scheduler_name(scheduler);
            EXPECT_EQ(check_sequence(back, p), "") << scheduler_name(scheduler);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Machines, RoundTrip,
                         testing::Values(Configuration{"default", 4, BusWord::quad, LineFifo::tdp_x2, true},
                                         Configuration{"six_pair_buses", 6, BusWord::pair, LineFifo::tdp, true},
                                         Configuration{"scalar_banked", 4, BusWord::scalar, LineFifo::banked, false},
                                         Configuration{"two_quad_buses", 2, BusWord::quad, LineFifo::tdp, false}),
                         [](const auto& info) { return std::string(info.param.name); });

// The default word: `last`, 4 buses x (1 + 6 + 6 + 4 lanes x 1 read), 18 TripleMACs x (1 take
// + 2 bus + 2 lane + 2 coefficient + 2 response) = 1 + 68 + 162 = 231 bits; fields tile the
// word without a gap. A lane's BRAM port is wiring (lane_port), not a field.
TEST(SequenceMemory, TheDefaultLayoutIs231Bits) {
    const MemoryLayout l = sequence_layout(SequenceParams{});
    EXPECT_EQ(l.width, 231);
    EXPECT_EQ(l.field("last").lsb, 0);
    EXPECT_EQ(l.field("bus0_line").lsb, 2);
    EXPECT_EQ(l.field("bus0_lane0_read").lsb, 14);
    EXPECT_EQ(l.field("bus0_lane3_read").lsb, 17);
    EXPECT_EQ(l.field("bus3_column").lsb, 59);
    EXPECT_EQ(l.field("mac0_take").lsb, 69);
    EXPECT_EQ(l.field("mac17_response").lsb, 229);
    int next = 0;
    for (const MemoryField& f : l.fields) EXPECT_EQ(f.lsb, std::exchange(next, f.lsb + f.width)) << f.name;
    EXPECT_EQ(next, l.width);
    SequenceParams scalar;
    scalar.bus_word = BusWord::scalar;
    scalar.read_buses = 6;  // 3 bus bits; the lane keeps one bit, so the RTL can always slice it
    EXPECT_EQ(sequence_layout(scalar).width, 1 + 6 * (13 + 1) + 18 * 9);
    scalar.line_fifo = LineFifo::sdp72;  // the organisation changes the wiring, not the word
    EXPECT_EQ(sequence_layout(scalar).width, 1 + 6 * (13 + 1) + 18 * 9);
}

// The hex text: the default's 231 bits are 58 digits, the last word's bit 0 is `last`.
TEST(SequenceMemory, FilesHoldOneHexWordPerCycle) {
    const SequenceParams p;
    const SequenceImage image = encode_sequence(cached_sequence(p), p);
    const std::string mem = to_readmemh(image, "t");
    const std::string last = mem.substr(mem.rfind('\n', mem.size() - 2) + 1);
    EXPECT_EQ(last.size(), 58u + 1);
    EXPECT_EQ(std::stoi(last.substr(57, 1), nullptr, 16) & 1, 1);
    const std::string coe = to_coe(image, "t");
    EXPECT_NE(coe.find("memory_initialization_radix=16;\nmemory_initialization_vector=\n"), std::string::npos);
    EXPECT_EQ(coe.substr(coe.size() - 2), ";\n");
}

// Words the encoder cannot write are refused, naming the word and the field.
TEST(SequenceMemory, DecodingRefusesWhatTheEncoderCannotWrite) {
    const SequenceParams p;
    const SequenceImage good = encode_sequence(cached_sequence(p), p);
    const MemoryLayout& l = good.layout;
    auto refusal = [&](auto&& change) {
        SequenceImage bad = good;
        change(bad);
        try {
            decode_sequence(bad, p);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(refusal([&](SequenceImage& b) { set_field(b.words.back(), l.field("last"), 0); }),
              "sequence memory word " + std::to_string(good.words.size() - 1) + ": last is 0, but the image ends here");
    EXPECT_EQ(refusal([&](SequenceImage& b) { set_field(b.words[3], l.field("last"), 1); }),
              "sequence memory word 3: last is 1, but words follow");
    EXPECT_EQ(refusal([&](SequenceImage& b) {
                  set_field(b.words[0], l.field("bus1_valid"), 1);
                  set_field(b.words[0], l.field("bus1_line"), 60);
                  set_field(b.words[0], l.field("bus1_column"), 0);
              }),
              "sequence memory word 0: bus1_line 60, bus1_column 0 is outside the 52 x 52 window");
    EXPECT_EQ(refusal([&](SequenceImage& b) {
                  for (int bus = 0; bus < 4; ++bus)
                      for (const char* f : {"_valid", "_line", "_column"})
                          set_field(b.words[0], l.field("bus" + std::to_string(bus) + f), 0);
              }).substr(0, 27),
              "sequence memory word 0: mac");  // a TripleMAC takes from a bus that carries nothing
    size_t idle = 0;                           // a word in which TripleMAC 4 takes nothing
    while (field_value(good.words[idle], l.field("mac4_take"))) ++idle;
    EXPECT_EQ(refusal([&](SequenceImage& b) { set_field(b.words[idle], l.field("mac4_bus"), 2); }),
              "sequence memory word " + std::to_string(idle) + ": mac4 takes nothing but has fields set");
    // The reads: exactly the lanes taken, and one address a port. Buses 1 and 2 traded in a word
    // still give every TripleMAC its value, but through other ports.
    const size_t swap = word_a_swap_breaks(good, p, 1, 2);
    ASSERT_LT(swap, good.words.size());
    const std::string two = refusal([&](SequenceImage& b) { swap_buses(b, swap, 1, 2); });
    EXPECT_EQ(two.rfind("sequence memory word " + std::to_string(swap) + ": bus", 0), 0u) << two;
    EXPECT_NE(two.find(" read two addresses of one BRAM through port "), std::string::npos) << two;
    EXPECT_NE(two.find(", the port both are wired to"), std::string::npos) << two;
    size_t pair = 0;  // a word in which bus 0 reads two values of one line
    while (!field_value(good.words[pair], l.field("bus0_lane0_read")) ||
           !field_value(good.words[pair], l.field("bus0_lane1_read")))
        ++pair;
    EXPECT_EQ(
        refusal([&](SequenceImage& b) { set_field(b.words[pair], l.field("bus0_lane0_read"), 0); }),
        "sequence memory word " + std::to_string(pair) + ": bus0_lane0_read is 0, but a TripleMAC takes the value");
    EXPECT_EQ(refusal([&](SequenceImage&) {}), "accepted");
    EXPECT_THROW(decode_sequence(SequenceImage{l, {}}, p), std::invalid_argument);
}

// Text that is not an image of this layout: the line is named.
TEST(SequenceMemory, ParsingNamesTheLine) {
    const MemoryLayout l = sequence_layout(SequenceParams{});
    auto refusal = [&](const std::string& text) {
        try {
            parse_image(text, l);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const std::string one = std::string(57, '0') + "1";  // a word of 58 digits: bit 0
    const std::string bad = std::string(57, '0') + "z";
    EXPECT_EQ(refusal("// c\n" + one + "\n" + bad + "\n"), "line 3: '" + bad + "' is not hexadecimal");
    EXPECT_EQ(refusal("@10\n" + one + "\n"), "line 1: addresses (@) are not read: one word a line");
    EXPECT_EQ(refusal(one + "0\n"), "line 1: '" + one + "0' is not a word of 231 bits (58 hex digits; it has 59)");
    EXPECT_EQ(refusal("1\n"), "line 1: '1' is not a word of 231 bits (58 hex digits; it has 1)");
    EXPECT_EQ(refusal("8" + std::string(57, '0') + "\n"),
              "line 1: '8" + std::string(57, '0') + "' has bits above the word's 231");
    EXPECT_EQ(refusal("4" + std::string(57, '0') + "\n"), "accepted");  // bit 230, the top one
    EXPECT_EQ(refusal("memory_initialization_radix=2;\nmemory_initialization_vector=\n" + one + ";\n"),
              "line 1: only radix 16 is read (memory_initialization_radix=2;)");
    EXPECT_EQ(refusal("memory_initialization_radix=16;\nmemory_initialization_vector=\n" + one + ",\n" + one + "\n"),
              "the COE vector does not end with ';'");
    EXPECT_EQ(refusal("memory_initialization_radix=16;\nmemory_initialization_vector=\n" + one + ";\n"), "accepted");
    EXPECT_EQ(refusal("// nothing\n"), "no words");
}

}  // namespace
}  // namespace surfvp::fhg
