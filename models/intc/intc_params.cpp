// Intc's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "intc.h"

namespace surfvp {

const ParamTable<Intc::Params>& Intc::parameter_table() {
    using P = Params;
    static const ParamTable<P> table(
        {field<P>({"intc.inputs",
                   ParamKind::count,
                   "12",
                   1,
                   32,
                   {},
                   "Interrupt inputs of the XPS INTC",
                   "[S] ML507 DTS: xps_intc with 12 inputs"},
                  &P::inputs),
         register_latency<P>("intc", "XPS INTC registers", "a registered or a pipelined IPIF answer")});
    return table;
}

}  // namespace surfvp
