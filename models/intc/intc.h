#pragma once
// Interrupt controller with the XPS INTC registers (intc_regs.h), their behaviour in
// IntcRegisters: level-sensitive inputs latched into ISR, the output MER.ME && ISR & IER.
// Register accesses take no time of their own (the PLB transaction carries it).
#include <cstdint>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>

#include "intc_registers.h"
#include "models/common/statistics.h"
#include "models/common/parameter.h"
#include "models/common/register_target.h"
#include "models/common/tracer.h"
#include "models/common/units.h"

namespace surfvp {

class Intc : public sc_core::sc_module {
public:
    struct Params {
        unsigned inputs = 12;
        RegisterTiming registers;  // a register access: its cycles (block.register_latency) of PLB1's clock
    };
    // Its scenario parameters with the Params field each sets (intc_params.cpp).
    static const ParamTable<Params>& parameter_table();

    tlm_utils::simple_target_socket<Intc> regs;  // SPLB on PLB1
    sc_core::sc_vector<sc_core::sc_in<bool>> irq_in;
    sc_core::sc_out<bool> irq;  // to the CPU

    Intc(const sc_core::sc_module_name& name, const Params& params, Tracer& tracer);

    uint64_t interrupts_raised() const { return raised_; }

    // Its statistics, registered at elaboration (after every connection) under `scope`.
    void register_statistics(const Statistics::Scope& scope) const;

private:
    void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
    void trace_line(bool level);
    unsigned transport_dbg(tlm::tlm_generic_payload& tx);
    uint32_t levels() const;
    void update();  // the only writer of `irq`

    Params params_;
    Tracer& tracer_;
    IntcRegisters registers_;
    uint64_t raised_ = 0;
    sc_core::sc_event changed_;
    int track_ = -1;
    int line_track_ = -1;         // the line to the CPU: a slice while it is high
    sc_core::sc_time raised_at_;  // when it last went high
    uint32_t raised_lines_ = 0;   // the lines pending then
    uint64_t flow_ = 0;           // the flow from its rise to the CPU's handling
};

}  // namespace surfvp
