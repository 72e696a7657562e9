#pragma once
// Physical quantities that scenario parameters carry, and the one place that parses them
// from text ("100 MHz", "128 bit", "16 beats", "2 ns", "64 KiB"). Plain C++: no SystemC,
// so cores, the scenario loader and tests share it.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace surfvp {

// Thrown when a text does not parse as the quantity asked for; the message names the
// expected units and is meant to be shown to the user as it is.
struct UnitError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Frequency {
    double hz = 0;
    // Period in picoseconds (SystemC's default time resolution).
    double period_ps() const { return 1e12 / hz; }
};

struct Duration {
    uint64_t ps = 0;
    double seconds() const { return static_cast<double>(ps) * 1e-12; }
};

struct Bytes {
    uint64_t n = 0;
};

// The kinds of value a parameter can hold; each unit-carrying kind accepts only its units.
enum class UnitKind { frequency, duration, bits, bytes, cycles, beats };

Frequency parse_frequency(const std::string& text);  // Hz kHz MHz GHz
Duration parse_duration(const std::string& text);    // ps ns us ms s
unsigned parse_bits(const std::string& text);        // bit bits
Bytes parse_bytes(const std::string& text);          // B KiB MiB GiB
uint64_t parse_cycles(const std::string& text);      // cycle cycles
unsigned parse_beats(const std::string& text);       // beat beats

// The canonical text of a value, which parses back to the same value: exactly for durations
// and sizes, to a relative 1e-9 for frequencies, which are written as a whole number of a unit
// when within 1e-9 of one ("8.2762 MHz" parses to 8276199.999999999 Hz, written "8276200 Hz").
std::string format_frequency(Frequency f);
std::string format_duration(Duration d);
std::string format_bytes(Bytes b);

}  // namespace surfvp
