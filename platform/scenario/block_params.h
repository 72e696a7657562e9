#pragma once
// Each block's Params from a configuration, built in this one place: the block's own
// declarations (its parameter_table) and what the wiring adds (the bus its registers answer
// on, the width of the bus its DMA masters, the simulation settings). The SoC builds its
// blocks from these; seqgen, the consistency checks and the reports read the same.
#include <string>
#include <systemc>

#include "models/dma/dma.h"
#include "models/fhg/fhg.h"
#include "models/iig/iig.h"
#include "models/intc/intc.h"
#include "models/mci/mci_link.h"
#include "models/memory/ddr_memory.h"
#include "models/plb/plb_bus.h"
#include "models/ppc440/ppc440.h"
#include "platform/scenario/config.h"

namespace surfvp {

PlbBus::Params plb_params(const Config& config, const std::string& bus);  // "plb1" or "plb2"
DdrMemory::Params memory_params(const Config& config);
MciLink::Params mci_params(const Config& config);
Intc::Params intc_params(const Config& config);
Dma::Params dma_params(const Config& config);
Iig::Params iig_params(const Config& config);
Fhg::Params fhg_params(const Config& config);
Ppc440::Params cpu_params(const Config& config);  // without the software's markers

// Whether the CPU reaches DDR over PLB1 (a what-if) rather than its MCI link.
bool cpu_memory_on_plb1(const Config& config);

// Line fills on the CPU's memory path with nothing else on it, by the models' own formulas
// (direct mode charges these): one fill (the MCI link, or PLB1, and the DDR's read), how far
// apart the path takes fills in flight together, how much sooner the missed word comes than
// the whole line, and how many fills may be in flight.
struct FillTiming {
    sc_core::sc_time fill, spacing, critical_word_lead;
    unsigned outstanding = 1;
    // The CPU's wait for a burst of n fills asked at once (Ppc440::compute's rule).
    sc_core::sc_time burst_stall(size_t n) const;
};
FillTiming uncontended_fills(const Config& config);

}  // namespace surfvp
