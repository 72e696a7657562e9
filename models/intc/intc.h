#pragma once
// Interrupt controller with the XPS INTC register layout (intc_regs.h). Inputs are level
// sensitive and active high: while an input is high and hardware interrupts are enabled
// (MER.HIE), its ISR bit is set, and acknowledging it (IAR) while the input is still high
// sets it again. The output to the CPU is MER.ME && (ISR & IER) != 0. Register accesses
// take no time of their own (the PLB transaction carries it).
#include <cstdint>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>

#include "models/common/tracer.h"
#include "models/common/units.h"

namespace surfvp {

class Intc : public sc_core::sc_module {
public:
    struct Params {
        unsigned inputs = 12;
        Duration register_latency{};  // a register access, as PLB1 sees it
    };

    tlm_utils::simple_target_socket<Intc> regs;  // SPLB on PLB1
    sc_core::sc_vector<sc_core::sc_in<bool>> irq_in;
    sc_core::sc_out<bool> irq;  // to the CPU

    Intc(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer);

    uint64_t interrupts_raised() const { return raised_; }

private:
    void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
    unsigned transport_dbg(tlm::tlm_generic_payload& tx);
    bool access(uint32_t offset, uint32_t& value, bool write);
    void latch_inputs();
    void update();  // the only writer of `irq`

    Params params_;
    Tracer& tracer_;
    uint32_t isr_ = 0, ier_ = 0, mer_ = 0;
    uint64_t raised_ = 0;
    sc_core::sc_event changed_;
    int track_ = -1;
};

}  // namespace surfvp
