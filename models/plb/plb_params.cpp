// A PLB's scenario parameters: each with its kind, default, range, description, source
// (and assumption band), bound to the Params field it sets.
#include "plb_bus.h"

namespace surfvp {

ParamTable<PlbBus::Params> PlbBus::parameter_table(const std::string& bus, const std::string& width,
                                                   const std::string& width_source, const std::string& role) {
    using P = Params;
    const bool dma_bus = bus == "plb2";
    return ParamTable<P>({
        field<P>({bus + ".clock",
                  ParamKind::frequency,
                  "100 MHz",
                  1 * unit::MHz,
                  1000 * unit::MHz,
                  {},
                  role + " bus clock",
                  "[S] ML507 design: PLB at 100 MHz (mch-plb-clk-period-ps = 10000)"},
                 &P::clock),
        field<P>(
            {bus + ".width",
             ParamKind::bits,
             width,
             32,
             128,
             {},
             role + " data width: 32, 64 or 128 bit",
             width_source,
             dma_bus ? ParamSpec::Band{"64 bit", "128 bit",
                                       "\"increased capacity\" could be 64 bit (docs/sources.md#arithmetic: enough)"}
                     : ParamSpec::Band{}},
            &P::width_bits),
        field<P>({bus + ".max_burst",
                  ParamKind::beats,
                  "16 beats",
                  2,
                  16,
                  {},
                  "Longest fixed-length burst; longer transactions are split",
                  "[S] Xilinx DS711/DS561: fixed bursts of 2-16 beats"},
                 &P::max_burst_beats),
        choice<P>({bus + ".arbitration",
                   ParamKind::choice,
                   "round_robin",
                   0,
                   0,
                   {},
                   "Arbitration among masters (fixed priority: the first master connected wins)",
                   "[A] PLB v4.6 supports both; round robin treats the masters alike",
                   {"fixed_priority", "round_robin", "the other PLB v4.6 arbitration mode"}},
                  &P::arbitration,
                  std::vector<std::pair<std::string, Arbitration>>{{"round_robin", Arbitration::round_robin},
                                                                   {"fixed_priority", Arbitration::fixed_priority}}),
        field<P>(
            {bus + ".arbitration_latency",
             ParamKind::cycles,
             "3 cycles",
             0,
             64,
             {},
             "Request-to-grant cycles paid by every burst",
             "[A] ~3-4 cycles of arbitration overhead per burst, not retrieved (docs/sources.md#plb)",
             {"1 cycle", "4 cycles",
              dma_bus ? "as plb1.arbitration_latency"
                      : "~3-4 cycles, not retrieved (docs/sources.md#plb); overlapped arbitration would hide most"}},
            &P::arbitration_cycles),
        field<P>({bus + ".address_latency",
                  ParamKind::cycles,
                  "1 cycle",
                  0,
                  64,
                  {},
                  "Address-phase cycles paid by every burst (no address pipelining modelled)",
                  "[A] one address cycle; with arbitration, 4 cycles of overhead per burst",
                  {"0 cycles", "2 cycles",
                   dma_bus ? "as plb1.address_latency"
                           : "address pipelining would hide it; a slow slave decode would add one"}},
                 &P::address_cycles),
    });
}

}  // namespace surfvp
