#include "platform/scenario/block_params.h"

#include <algorithm>

#include "platform/scenario/run_settings.h"

namespace surfvp {
namespace {

// The register slaves are on PLB1: their answers are in its cycles.
template <typename Params>
Params on_plb1(Params p, const Config& c) {
    p.registers.bus_clock = c.frequency("plb1.clock");
    return p;
}

// One TLM transaction per line (fast) or per burst (finest contention).
uint64_t dma_transaction_bytes(const Config& c, unsigned burst_beats) {
    return run_settings(c).dma_per_burst ? uint64_t(burst_beats) * plb_params(c, "plb2").width_bits / 8 : 0;
}

}  // namespace

PlbBus::Params plb_params(const Config& c, const std::string& bus) {
    for (const PlbDeclaration& d : plb_declarations()) {
        if (d.bus != bus) continue;
        PlbBus::Params p = d.table.make(c);
        p.series_bin = run_settings(c).series_bin;
        if (p.width_bits != 32 && p.width_bits != 64 && p.width_bits != 128)
            throw ConfigError(bus + ".width: a PLB is 32, 64 or 128 bit wide");
        return p;
    }
    throw std::logic_error("no PLB named " + bus);
}

DdrMemory::Params memory_params(const Config& c) {
    DdrMemory::Params p = DdrMemory::parameter_table().make(c);
    const RunSettings run = run_settings(c);
    p.series_bin = run.series_bin;
    p.populate_ahead = run.parallel;
    return p;
}
MciLink::Params mci_params(const Config& c) { return MciLink::parameter_table().make(c); }

bool cpu_memory_on_plb1(const Config& c) { return run_settings(c).cpu_memory_on_plb1; }

Intc::Params intc_params(const Config& c) { return on_plb1(Intc::parameter_table().make(c), c); }

Dma::Params dma_params(const Config& c) {
    Dma::Params p = on_plb1(Dma::parameter_table().make(c), c);
    p.bus_width_bits = c.bits("plb2.width");
    return p;
}

// A block's own parameters from its declarations; the wiring adds the bus it is on and the
// simulation setting of its DMA.
Iig::Params iig_params(const Config& c) {
    Iig::Params p = on_plb1(Iig::parameter_table().make(c), c);
    p.bus_width_bits = c.bits("plb2.width");
    p.dma_transaction_bytes = dma_transaction_bytes(c, p.burst_beats);
    return p;
}

Fhg::Params fhg_params(const Config& c) {
    Fhg::Params p = on_plb1(Fhg::parameter_table().make(c), c);
    p.bus_width_bits = c.bits("plb2.width");
    const RunSettings run = run_settings(c);
    p.parallel = run.parallel;
    p.series_bin = run.series_bin;
    p.dma_transaction_bytes = dma_transaction_bytes(c, p.burst_beats);
    return p;
}

FillTiming uncontended_fills(const Config& c) {
    const uint64_t line = Ppc440::parameter_table().make(c).line_bytes;  // cpu_params adds these fills
    const DdrMemory::Params memory = memory_params(c);
    const sc_core::sc_time ddr = DdrMemory::read_time(memory, line);
    FillTiming t;
    if (cpu_memory_on_plb1(c)) {
        t.fill = t.spacing = PlbBus::burst_time(plb_params(c, "plb1"), line, ddr);  // PLB1 takes one at a time
    } else {
        const MciLink::Params mci = mci_params(c);
        t.fill = MciLink::access_time(mci, line, ddr);
        t.spacing = MciLink::own_time(mci, line);
    }
    const Ppc440::Params cpu = Ppc440::parameter_table().make(c);
    t.outstanding = cpu.outstanding_fills;
    if (cpu.critical_word_first) {  // the missed word comes with the DRAM's first transfer, the rest after it
        const double rest = double(line) - std::min<double>(double(line), memory.width_bits / 8.0);
        t.critical_word_lead = sc_core::sc_time(rest / DdrMemory::bytes_per_second(memory), sc_core::SC_SEC);
    }
    return t;
}

sc_core::sc_time FillTiming::burst_stall(size_t n) const {
    std::vector<sc_core::sc_time> start(n), end(n);
    sc_core::sc_time data = sc_core::SC_ZERO_TIME;
    for (size_t k = 0; k < n; ++k) {
        start[k] = k ? start[k - 1] + spacing : sc_core::SC_ZERO_TIME;
        if (k >= outstanding) start[k] = std::max(start[k], end[k - outstanding]);
        end[k] = start[k] + fill;
        data = std::max(data, end[k] - critical_word_lead);
    }
    return data;
}

Ppc440::Params cpu_params(const Config& c) {
    Ppc440::Params p = Ppc440::parameter_table().make(c);
    p.critical_word_lead = Duration{uncontended_fills(c).critical_word_lead.value()};
    return p;
}

}  // namespace surfvp
