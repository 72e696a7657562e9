#pragma once
// The SoC of the paper's Fig. 3, built from a configuration: it instantiates the blocks,
// binds their sockets and interrupt lines, and maps their regions from address_map.h.
// It holds no behaviour of its own.
#include <memory>
#include <optional>
#include <vector>
#include <systemc>

#include "platform/scenario/block_params.h"
#include "models/common/statistics.h"
#include "models/common/tracer.h"
#include "models/dma/dma.h"
#include "models/fhg/fhg.h"
#include "models/iig/iig.h"
#include "models/intc/intc.h"
#include "models/mci/mci_link.h"
#include "models/memory/ddr_memory.h"
#include "models/plb/plb_bus.h"
#include "models/ppc440/ppc440.h"
#include "platform/workload/workload.h"

namespace surfvp {

// The register tables of the chip's blocks with their place in the address map, for
// docs/registers.md (`surfvp registers`).
std::vector<MappedRegisters> chip_registers();

class Soc {
public:
    Soc(const Config& config, Tracer& tracer);  // elaborates; throws ConfigError

    Ppc440& cpu() { return *cpu_; }
    DdrMemory& memory() { return *memory_; }
    const std::vector<std::unique_ptr<Iig>>& iigs() const { return iigs_; }
    const std::vector<std::unique_ptr<Fhg>>& fhgs() const { return fhgs_; }
    Workload& workload() { return *workload_; }

    // Every block's statistics, registered at elaboration (platform/report renders them).
    const Statistics& statistics() const { return statistics_; }
    uint64_t bus_transactions() const;

private:
    void build(const Config& config, Tracer& tracer);
    void wire_interrupts(Tracer& tracer);
    void register_statistics();

    Statistics statistics_;
    FaultPlan faults_;
    std::unique_ptr<Workload> workload_;
    std::unique_ptr<DdrMemory> memory_;
    std::unique_ptr<PlbBus> plb1_, plb2_;
    std::unique_ptr<MciLink> mci_;
    std::string cpu_memory_path_;  // "mci" or "plb1"
    std::unique_ptr<Intc> intc_;
    std::unique_ptr<Dma> dma_;
    std::vector<std::unique_ptr<Iig>> iigs_;
    std::vector<std::unique_ptr<Fhg>> fhgs_;
    std::unique_ptr<Ppc440> cpu_;
    // The first FHG's worker lent to the software; declared after the blocks and the memory,
    // so the loan ends before they go.
    std::optional<WorkerLoan> loan_;
    sc_core::sc_signal<bool> dma_irq_{"dma_irq"}, cpu_irq_{"cpu_irq"}, low_{"unused_irq"};
    sc_core::sc_vector<sc_core::sc_signal<bool>> iig_irqs_{"iig_irq"}, fhg_irqs_{"fhg_irq"};
};

}  // namespace surfvp
