// Parsing quantities with units: the one place text becomes typed values.
#include <gtest/gtest.h>

#include "models/common/units.h"

namespace surfvp {
namespace {

TEST(Units, ParsesEachKindInItsUnits) {
    EXPECT_DOUBLE_EQ(parse_frequency("100 MHz").hz, 100e6);
    EXPECT_DOUBLE_EQ(parse_frequency("1.5GHz").hz, 1.5e9);
    EXPECT_EQ(parse_duration("2 ns").ps, 2000u);
    EXPECT_EQ(parse_duration("1 us").ps, 1000000u);
    EXPECT_EQ(parse_bits("128 bit"), 128u);
    EXPECT_EQ(parse_bytes("64 KiB").n, 65536u);
    EXPECT_EQ(parse_bytes("256 MiB").n, 256u << 20);
    EXPECT_EQ(parse_cycles("3 cycles"), 3u);
    EXPECT_EQ(parse_cycles("1 cycle"), 1u);
    EXPECT_EQ(parse_beats("16 beats"), 16u);
}

void expect_error(void (*parse)(), const std::string& words) {
    try {
        parse();
        FAIL() << "no error; expected one mentioning " << words;
    } catch (const UnitError& e) {
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
}

TEST(Units, ErrorsSayWhatIsWrong) {
    expect_error([] { parse_frequency("100"); }, "has no unit");
    expect_error([] { parse_frequency("100 parsecs"); }, "wrong unit 'parsecs'");
    expect_error([] { parse_bits("128 MHz"); }, "takes bit, bits");
    expect_error([] { parse_duration("fast"); }, "is not a duration");
    expect_error([] { parse_cycles("2.5 cycles"); }, "not a whole number");
    expect_error([] { parse_bytes("-4 KiB"); }, "negative");
    expect_error([] { parse_frequency("0 Hz"); }, "above zero");
    // A value its type cannot hold is out of range, never wrapped (4294967306 = 2^32 + 10).
    expect_error([] { parse_bits("4294967306 bit"); }, "out of range");
    expect_error([] { parse_cycles("1e30 cycles"); }, "out of range");
    expect_error([] { parse_beats("5e9 beats"); }, "out of range");
    expect_error([] { parse_frequency("inf MHz"); }, "is not a frequency");
    expect_error([] { parse_duration("nan s"); }, "is not a duration");
}

TEST(Units, FormatParsesBackToTheSameValue) {
    for (double hz : {100e6, 133.33e6, 1e9, 12345.0})
        EXPECT_DOUBLE_EQ(parse_frequency(format_frequency(Frequency{hz})).hz, hz) << format_frequency(Frequency{hz});
    EXPECT_EQ(format_frequency(Frequency{100e6}), "100 MHz");
    EXPECT_EQ(format_duration(Duration{1000000}), "1 us");
    EXPECT_EQ(format_bytes(Bytes{65536}), "64 KiB");
    EXPECT_EQ(format_bytes(Bytes{1000}), "1000 B");
}

}  // namespace
}  // namespace surfvp
