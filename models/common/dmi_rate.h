#pragma once
// TLM-2.0 DMI carries one latency per access; bulk DMI users (the CPU stub's memory copies)
// also need the streaming rate: a DMI access of N bytes is charged latency +
// transfer_time(N, rate). That is exactly a b_transport's time at the memory; through a bus
// it is one burst's arbitration and address overhead, not one per burst, so long copies come
// out shorter than a sequence of bursts would (about 20 % for 64 KiB over PLB1). The initiator
// attaches this extension to its DMI request; each target or interconnect on the way lowers
// the rate to its own. A component that does not know it ignores it (ignorable extension).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <tlm>

namespace surfvp {

// The one formula for streaming `bytes` at `bytes_per_second`, rounded once to the
// simulator's resolution; targets use it too, so DMI and b_transport agree to the picosecond.
inline sc_core::sc_time transfer_time(uint64_t bytes, double bytes_per_second) {
    return sc_core::sc_time(double(bytes) / bytes_per_second, sc_core::SC_SEC);
}

struct DmiRate : tlm::tlm_extension<DmiRate> {
    double bytes_per_second = std::numeric_limits<double>::infinity();

    void limit(double rate) { bytes_per_second = std::min(bytes_per_second, rate); }
    tlm::tlm_extension_base* clone() const override { return new DmiRate(*this); }
    void copy_from(const tlm::tlm_extension_base& other) override {
        bytes_per_second = static_cast<const DmiRate&>(other).bytes_per_second;
    }
};

}  // namespace surfvp
