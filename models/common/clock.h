#pragma once
// Turns cycle counts at a clock into SystemC time. The product is rounded once, at the
// simulator's resolution (1 ps), so long counts at clocks with a fractional period in
// picoseconds do not accumulate rounding.
#include <systemc>

#include "units.h"

namespace surfvp {

inline sc_core::sc_time cycles(Frequency clock, double count) {
    return sc_core::sc_time(count * clock.period_ps(), sc_core::SC_PS);
}

}  // namespace surfvp
