#pragma once
// Turns cycle counts at a clock, and bytes at a rate, into SystemC time. Each product is
// rounded once, at the simulator's resolution (1 ps), so long counts at clocks with a
// fractional period in picoseconds do not accumulate rounding.
#include <cstdint>
#include <systemc>

#include "units.h"

namespace surfvp {

inline sc_core::sc_time cycles(Frequency clock, double count) {
    return sc_core::sc_time(count * clock.period_ps(), sc_core::SC_PS);
}

// Streaming `bytes` at `bytes_per_second`.
inline sc_core::sc_time transfer_time(uint64_t bytes, double bytes_per_second) {
    return sc_core::sc_time(double(bytes) / bytes_per_second, sc_core::SC_SEC);
}

}  // namespace surfvp
