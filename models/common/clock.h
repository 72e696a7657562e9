#pragma once
// Turns cycle counts at a clock, and bytes at a rate, into SystemC time. Each product is
// rounded once, at the simulator's resolution (1 ps), so long counts at clocks with a
// fractional period in picoseconds do not accumulate rounding.
#include <cstdint>
#include <systemc>

#include "units.h"

namespace surfvp {

// sc_time(ps, SC_PS) at the 1 ps resolution, rounded the same way (half up), without the
// constructor's look-up of the simulation context: that look-up was 5 % of a simulation's
// time, as these conversions run once or more per bus transaction.
inline sc_core::sc_time picoseconds(double ps) {
    static const sc_core::sc_time one = sc_core::sc_time::from_value(1);
    return one * ps;  // sc_time's own multiply: int64(1.0 x ps + 0.5)
}

inline sc_core::sc_time cycles(Frequency clock, double count) { return picoseconds(count * clock.period_ps()); }

// Streaming `bytes` at `bytes_per_second`.
inline sc_core::sc_time transfer_time(uint64_t bytes, double bytes_per_second) {
    return picoseconds(double(bytes) / bytes_per_second * 1e12);  // sc_time(s, SC_SEC) scales by 1e12 the same way
}

}  // namespace surfvp
