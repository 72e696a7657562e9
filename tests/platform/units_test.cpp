// Parsing quantities with units: the one place text becomes typed values.
#include <gtest/gtest.h>

#include <random>

#include "models/common/clock.h"
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
    // Found by tests/fuzz (units): 2^64 passed the check against double(UINT64_MAX), which is
    // 2^64 itself, and the conversion to uint64_t was undefined.
    expect_error([] { parse_duration("18446744073709551616 ps"); }, "out of range");
    expect_error([] { parse_bytes("16 EiB"); }, "wrong unit");
    expect_error([] { parse_bytes("17179869184 GiB"); }, "out of range");  // 2^64 B
}

TEST(Units, FormatParsesBackToTheSameValue) {
    for (double hz : {100e6, 133.33e6, 1e9, 12345.0})
        EXPECT_DOUBLE_EQ(parse_frequency(format_frequency(Frequency{hz})).hz, hz) << format_frequency(Frequency{hz});
    EXPECT_EQ(format_frequency(Frequency{100e6}), "100 MHz");
    EXPECT_EQ(format_duration(Duration{1000000}), "1 us");
    EXPECT_EQ(format_bytes(Bytes{65536}), "64 KiB");
    EXPECT_EQ(format_bytes(Bytes{1000}), "1000 B");
    // Found by tests/fuzz (units): a whole number of a unit too large for uint64_t (a frequency
    // has no upper bound) was converted to one; now it is written as a real number.
    const Frequency huge{1.18228e122};
    EXPECT_DOUBLE_EQ(parse_frequency(format_frequency(huge)).hz, huge.hz) << format_frequency(huge);
    // units.h's 1e-12: "8.2762 MHz" is 8276199.999999999 Hz, written as the whole 8276200 Hz.
    const Frequency f = parse_frequency("8.2762 MHz");
    EXPECT_EQ(format_frequency(f), "8276200 Hz");
    EXPECT_NEAR(parse_frequency(format_frequency(f)).hz, f.hz, 1e-12 * f.hz);
    // Found by tests/fuzz (units): a duration within 1e-9 of a whole number of seconds was
    // written as that number, 208 ps lost; durations and sizes are integers, written exactly.
    const Duration d = parse_duration("10000000000208 ps");
    EXPECT_EQ(parse_duration(format_duration(d)).ps, d.ps) << format_duration(d);
}

// The fast conversions give what SystemC's own constructors give, to the picosecond,
// including the halves that round up and clocks with fractional periods.
TEST(Units, TimeConversionsRoundLikeSystemC) {
    std::mt19937_64 random(3);
    for (int i = 0; i < 20000; ++i) {
        const double ps = (i < 100) ? i * 0.5 : double(random() % 100000000) / double(1 + random() % 1000);
        ASSERT_EQ(picoseconds(ps), sc_core::sc_time(ps, sc_core::SC_PS)) << ps;
    }
    for (double mhz : {100.0, 125.0, 133.333, 266.0, 400.0})
        for (double n : {0.0, 1.0, 3.0, 7.5, 1e3, 12345.0, 1e7})
            ASSERT_EQ(cycles(Frequency{mhz * 1e6}, n),
                      sc_core::sc_time(n * Frequency{mhz * 1e6}.period_ps(), sc_core::SC_PS))
                << mhz << " " << n;
    for (uint64_t bytes : {0u, 1u, 4u, 32u, 128u, 4096u, 786432u})
        for (double rate : {400e6, 800e6, 1.6e9, 3.2e9 / 3})
            ASSERT_EQ(transfer_time(bytes, rate), sc_core::sc_time(double(bytes) / rate, sc_core::SC_SEC))
                << bytes << " " << rate;
}

}  // namespace
}  // namespace surfvp
