#pragma once
// A standalone memory-to-memory DMA: the test master of the smoke scenario, built from the
// same DmaEngine the IP blocks embed. The CPU programs SRC, DST and LEN over PLB1 and
// writes CTRL.START; the block copies through a one-burst buffer (read a burst, write it)
// over its MPLB port on PLB2, then sets STATUS.DONE (or ERROR with a code) and raises its
// interrupt if CTRL.IRQ_EN. Registers in dma_regs.h.
#include <cstdint>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <vector>

#include "dma_engine.h"
#include "models/common/statistics.h"
#include "models/common/parameter.h"
#include "models/common/register_target.h"
#include "models/common/register_bank.h"
#include "models/common/tracer.h"
#include "models/common/units.h"

namespace surfvp {

class Dma : public sc_core::sc_module {
public:
    struct Params {
        unsigned burst_beats = 16;
        unsigned bus_width_bits = 128;  // of the bus the MPLB port is on
        RegisterTiming registers;       // a register access: its cycles (block.register_latency) of PLB1's clock
    };
    // Its scenario parameters with the Params field each sets (dma_params.cpp).
    static const ParamTable<Params>& parameter_table();

    tlm_utils::simple_target_socket<Dma> regs;     // SPLB on PLB1
    tlm_utils::simple_initiator_socket<Dma> mplb;  // bursts on PLB2
    sc_core::sc_out<bool> irq;

    Dma(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer);

    uint64_t bytes_copied() const { return bytes_copied_; }
    uint64_t copies() const { return copies_; }

    // Its statistics, registered at elaboration (after every connection) under `scope`.
    void register_statistics(const Statistics::Scope& scope) const;

private:
    void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
    void bind_registers();
    bool access(uint32_t offset, uint32_t& value, bool write);
    uint32_t& reg(uint32_t offset) { return bank_.value(offset); }
    void copy_thread();
    void fail(uint32_t code, uint64_t address);
    void update_irq();  // the only writer of `irq`

    Params params_;
    Tracer& tracer_;
    RegisterBank bank_;  // dma_regs.h's table
    sc_core::sc_event start_, irq_changed_;
    sc_core::sc_signal<bool> busy_{"busy"};
    std::vector<uint8_t> buffer_;  // one burst
    uint64_t bytes_copied_ = 0, copies_ = 0;
    int track_ = -1;
};

}  // namespace surfvp
