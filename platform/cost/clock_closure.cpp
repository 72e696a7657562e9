#include "platform/cost/clock_closure.h"

#include <fmt/format.h>

#include "models/fhg/fhg.h"
#include "platform/cost/fpga_resources.h"
#include "platform/scenario/block_params.h"

namespace surfvp {

// The line FIFO's block RAM runs at fhg.clock times its organisation's multiple (tdp_x2: two
// reads a port and FHG cycle), and must stay under the device's block-RAM maximum.
ClockClosure clock_closure(const Config& c) {
    ClockClosure r;
    const FpgaDevice device = fpga_device(c);
    const Fhg::Params fhg = fhg_params(c);
    const fhg::LineFifo fifo = fhg.sequence.line_fifo;
    const int multiple = fhg::line_fifo_shape(fifo).clock_multiple;
    r.domains.push_back(
        {"FHG line FIFO block RAM", fhg.clock.hz * multiple, device.bram_fmax.hz,
         fmt::format("{} x fhg.clock ({}) against fpga.bram_fmax", multiple, fhg::line_fifo_name(fifo))});
    for (const ClockDomain& d : r.domains)
        if (!d.closes())
            r.failing.push_back(fmt::format("{}: {:g} MHz, above its {:g} MHz ({})", d.name, d.clock_hz / 1e6,
                                            d.fmax_hz / 1e6, d.basis));
    return r;
}

nlohmann::ordered_json closure_json(const ClockClosure& closure) {
    nlohmann::ordered_json domains = nlohmann::ordered_json::array();
    for (const ClockDomain& d : closure.domains)
        domains.push_back({{"name", d.name},
                           {"clock_mhz", d.clock_hz / 1e6},
                           {"fmax_mhz", d.fmax_hz / 1e6},
                           {"margin", d.fmax_hz / d.clock_hz - 1},
                           {"closes", d.closes()},
                           {"basis", d.basis}});
    return {{"closes", closure.closes()}, {"failing", closure.failing}, {"domains", domains}};
}

}  // namespace surfvp
