#pragma once
// Round-number ticks for a chart's axis: 1, 2 or 5 times a power of ten, so that a reader
// reads 0, 2, 4, 6, 8, 10 frames/s rather than 3.14, 6.29, 9.43. The sweep's plots and
// report.html's charts use them.
#include <string>
#include <vector>

namespace surfvp {

struct Ticks {
    std::vector<double> at;  // from the first at or below lo to the first at or above hi
    double step = 1;
    double lo() const { return at.front(); }
    double hi() const { return at.back(); }
};

// About `count` intervals over [lo, hi] (hi > lo; a zero span is widened).
Ticks round_ticks(double lo, double hi, int count = 5);

// A tick's label with the digits its step needs ("0.25", "10", "1.5").
std::string tick_label(double value, double step);

}  // namespace surfvp
