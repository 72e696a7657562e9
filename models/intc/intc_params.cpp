// Intc's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "intc.h"

namespace surfvp {

const ParamTable<Intc::Params>& Intc::parameter_table() {
    using P = Params;
    static const ParamTable<P> table({
        field<P>({"intc.inputs", ParamKind::count, "12", 1, 32, {}, "Interrupt inputs of the XPS INTC",
           "[S] ML507 DTS: xps_intc with 12 inputs"},
                 &P::inputs),
        field<P>({"intc.register_latency", ParamKind::cycles, "2 cycles", 0, 64, {},
           "XPS INTC registers: PLB1 cycles from the address phase to the register's data",
           "[A] an XPS PLBv46 slave (IPIF) decodes the address and registers its data: a few cycles (DS561 "
           "timing not retrieved)",
           {"1 cycle", "4 cycles",
            "a registered or a pipelined IPIF answer"}},
                 [](P& p) -> unsigned& { return p.registers.cycles; })
    });
    return table;
}

}  // namespace surfvp
