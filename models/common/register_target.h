#pragma once
// Answers a register access carried by a TLM transaction, for every register slave alike:
// registers are 32-bit words at word-aligned offsets, read and written whole, big-endian on
// the bus (see byte_order.h). Anything else is answered with the TLM error response that
// names what was wrong, never an assert.
#include <cmath>
#include <cstdint>
#include <tlm>
#include <type_traits>

#include "byte_order.h"
#include "clock.h"
#include "parameter.h"
#include "units.h"

namespace surfvp {

// How long a register slave takes to answer: `cycles` of the clock of the bus its SPLB is on
// (the cycles are the block's parameter; the wiring tells it the bus clock).
struct RegisterTiming {
    unsigned cycles = 0;
    Frequency bus_clock{100e6};
    Duration latency() const { return Duration{uint64_t(std::llround(double(cycles) * bus_clock.period_ps()))}; }
};

// A register slave's `block.register_latency` parameter, the same for every block but its
// name, what it answers for ("SSA IIG registers") and the reason of its band.
template <typename Params>
ParamField<Params> register_latency(const std::string& block, const std::string& what, const std::string& band_why) {
    return field<Params>(
        {block + ".register_latency",
         ParamKind::cycles,
         "2 cycles",
         0,
         64,
         {},
         what + ": PLB1 cycles from the address phase to the register's data",
         "[A] an XPS PLBv46 slave (IPIF) decodes the address and registers its data: a few cycles (DS561 "
         "timing not retrieved)",
         {"1 cycle", "4 cycles", band_why}},
        [](Params& p) -> unsigned& { return p.registers.cycles; });
}

// `access(offset, value, is_write)` reads into or writes from `value`; it returns false for
// an offset that holds no register. `access` is that function, or a register bank that has it
// as a member (a block's FhgRegisters, say).
template <typename Access>
bool access_register(Access& access, uint32_t offset, uint32_t& value, bool write) {
    if constexpr (std::is_invocable_v<Access&, uint32_t, uint32_t&, bool>)
        return access(offset, value, write);
    else
        return access.access(offset, value, write);
}

template <typename Access>
void answer_register_access(tlm::tlm_generic_payload& tx, Access&& access) {
    const bool whole_word = tx.get_data_length() == 4 && tx.get_streaming_width() == 4 && tx.get_address() % 4 == 0;
    if (tx.get_byte_enable_ptr() != nullptr) {
        tx.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
        return;
    }
    if (!whole_word) {
        tx.set_response_status(tlm::TLM_BURST_ERROR_RESPONSE);
        return;
    }
    const auto offset = static_cast<uint32_t>(tx.get_address());
    uint32_t value = 0;
    bool ok = false;
    if (tx.is_write()) {
        value = load_be32(tx.get_data_ptr());
        ok = access_register(access, offset, value, true);
    } else if (tx.is_read()) {
        ok = access_register(access, offset, value, false);
        if (ok) store_be32(tx.get_data_ptr(), value);
    } else {
        ok = true;  // TLM_IGNORE_COMMAND
    }
    tx.set_response_status(ok ? tlm::TLM_OK_RESPONSE : tlm::TLM_ADDRESS_ERROR_RESPONSE);
}

// The same over a bus: the slave takes `latency` to answer (its interface's decode and
// registered data), which the bus sees as the slave's time.
template <typename Access>
void answer_register_access(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay, const Duration& latency,
                            Access&& access) {
    answer_register_access(tx, std::forward<Access>(access));
    delay += picoseconds(double(latency.ps));
}

}  // namespace surfvp
