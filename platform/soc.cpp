#include "platform/soc.h"

#include <cmath>
#include <fmt/format.h>

#include "platform/address_map.h"
#include "platform/scenario/block_params.h"
#include "platform/scenario/run_settings.h"
#include "models/dma/dma_regs.h"
#include "models/fhg/fhg_regs.h"
#include "models/iig/iig_regs.h"
#ifdef SURFVP_WITH_RTL
#include "models/fhg/rtl/rtl_datapath.h"
#include "models/fhg/sequence_cache.h"
#endif
#include "models/intc/intc_regs.h"

namespace surfvp {
namespace {

// fhg.model=rtl: the verilated datapath running this configuration's sequence image (the
// scenario's checks have refused it already where the build cannot run it).
std::unique_ptr<fhg::Datapath> rtl_datapath(const Fhg::Params& p) {
#ifdef SURFVP_WITH_RTL
    const fhg::SequenceImage image = fhg::encode_sequence(fhg::cached_sequence(p.sequence), p.sequence);
    return std::make_unique<fhg::RtlDatapath>(p.precision, p.sequence, p.max_width, image);
#else
    (void)p;
    throw std::logic_error("fhg.model=rtl in a build without Verilator (check_consistency lets it through)");
#endif
}

}  // namespace

std::vector<MappedRegisters> chip_registers() {
    auto at = [](const map::Region& r, const char* bus) {
        return fmt::format("Its window is {:#010x} on {}", r.base, bus);
    };
    const std::string pairs = fmt::format(", pair k at + k x {:#x}", map::kAcceleratorStride);
    return {{&iig::table(), at(map::iig, "PLB1") + pairs},
            {&fhg_regs::table(), at(map::fhg, "PLB1") + pairs},
            {&intc::table(), at(map::intc, "PLB1") + fmt::format(" (inputs: DMA {}, IIG k {} + 2k, FHG k {} + 2k)",
                                                                 map::irq::dma, map::irq::iig(0), map::irq::fhg(0))},
            {&dma::table(), at(map::dma, "PLB1")}};
}

Soc::Soc(const Config& c, Tracer& tracer) : faults_(c.faults), workload_(make_workload(c)) {
    try {
        build(c, tracer);
    } catch (const std::invalid_argument& e) {
        // A model refused its parameters (an impossible FHG configuration, say).
        throw ConfigError(e.what());
    }
}

void Soc::build(const Config& c, Tracer& tracer) {
    const unsigned pairs = run_settings(c).accelerators;
    // The VCD's groups in GTKWave, in the order of the paper's Fig. 3.
    std::vector<std::pair<std::string, std::string>> titles{
        {"sw", "Tasks (libSSA2)"}, {"irq", "Interrupts"}, {"cpu", "PPC440"}};
    for (unsigned k = 0; k < pairs; ++k) {
        const std::string suffix = pairs > 1 ? std::to_string(k) : "";
        titles.emplace_back("iig" + suffix, "SSA IIG" + (suffix.empty() ? "" : " " + suffix));
        titles.emplace_back("fhg" + suffix, "SSA FHG" + (suffix.empty() ? "" : " " + suffix));
    }
    titles.insert(titles.end(),
                  {{"plb1", "PLB1 (CPU, registers)"}, {"plb2", "PLB2 (DMA traffic)"}, {"dma", "Test DMA"}});
    tracer.group_titles(std::move(titles));
    cpu_memory_path_ = cpu_memory_on_plb1(c) ? "plb1" : "mci";
    memory_ = std::make_unique<DdrMemory>("memory", memory_params(c));
    plb1_ = std::make_unique<PlbBus>("plb1", plb_params(c, "plb1"), tracer);
    plb2_ = std::make_unique<PlbBus>("plb2", plb_params(c, "plb2"), tracer);
    if (!cpu_memory_on_plb1(c)) mci_ = std::make_unique<MciLink>("mci", mci_params(c));
    intc_ = std::make_unique<Intc>("intc", intc_params(c), tracer);
    dma_ = std::make_unique<Dma>("dma", dma_params(c), tracer);
    for (unsigned k = 0; k < pairs; ++k) {
        const std::string suffix = pairs > 1 ? std::to_string(k) : "";
        iigs_.push_back(std::make_unique<Iig>(("iig" + suffix).c_str(), iig_params(c), tracer));
        fhgs_.push_back(std::make_unique<Fhg>(("fhg" + suffix).c_str(), fhg_params(c), tracer));
        const Fhg::Params& params = fhgs_.back()->params();
        if (params.model == fhg::DatapathModel::rtl) fhgs_.back()->use_datapath(rtl_datapath(params));
    }
    Ppc440::Params cpu = cpu_params(c);
    for (unsigned k = 0; k < pairs; ++k) cpu.markers.push_back(fmt::format("accelerator{}_task", k));
    cpu.markers.push_back("describing_task");
    cpu_ = std::make_unique<Ppc440>("cpu", cpu, workload_->software(), tracer);
    loan_.emplace(*workload_, fhgs_.empty() ? nullptr : fhgs_[0]->worker());
    const uint64_t ddr_size = memory_params(c).size.n;

    // PLB1: the CPU's MPLB; DDR, the INTC and the register slaves.
    plb1_->connect_master(cpu_->bus, "cpu");
    // The CPU's memory: its crossbar and MCI to the MPMC (or, as a what-if, PLB1).
    if (cpu_memory_on_plb1(c)) {
        plb1_->connect_master(cpu_->mem, "cpu memory");
    } else {
        cpu_->mem.bind(mci_->cpu);
    }
    unsigned slave = 0;
    auto attach = [&](auto& socket, uint64_t base, uint64_t size, const std::string& name) {
        plb1_->slaves.bind(socket);
        plb1_->map(base, size, slave++, name);
    };
    attach(memory_->ports, map::ddr.base, ddr_size, map::ddr.name);
    memory_->name_port("plb1");
    attach(intc_->regs, map::intc.base, map::intc.size, map::intc.name);
    attach(dma_->regs, map::dma.base, map::dma.size, map::dma.name);
    for (unsigned k = 0; k < pairs; ++k) {
        attach(iigs_[k]->regs, map::iig_base(k), map::iig.size, iigs_[k]->basename());
        attach(fhgs_[k]->regs, map::fhg_base(k), map::fhg.size, fhgs_[k]->basename());
    }

    // PLB2: the DMA masters to DDR.
    plb2_->connect_master(dma_->mplb, "dma", dma_params(c).burst_beats);
    for (unsigned k = 0; k < pairs; ++k) {
        plb2_->connect_master(iigs_[k]->mplb, iigs_[k]->basename(), iigs_[k]->params().burst_beats);
        plb2_->connect_master(fhgs_[k]->mplb, fhgs_[k]->basename(), fhgs_[k]->params().burst_beats);
        iigs_[k]->pixels.bind(fhgs_[k]->pixels);  // PixelBus: IIG -> FHG
    }
    plb2_->slaves.bind(memory_->ports);
    memory_->name_port("plb2");
    plb2_->map(map::ddr.base, ddr_size, 0, map::ddr.name);
    if (mci_) {
        mci_->memory.bind(memory_->ports);
        memory_->name_port("mci");
    }

    wire_interrupts(tracer);
    register_statistics();
    if (!faults_.empty()) {
        workload_->inject(faults_);
        plb2_->set_faults(&faults_);
        for (unsigned k = 0; k < pairs; ++k) {
            iigs_[k]->set_faults(&faults_, k);
            fhgs_[k]->set_faults(&faults_, k);
        }
    }
}

// Block lines into the INTC, the INTC into the CPU; unused inputs held low.
void Soc::wire_interrupts(Tracer& tracer) {
    const unsigned pairs = unsigned(iigs_.size());
    if (map::irq::fhg(pairs - 1) >= intc_->irq_in.size())
        throw ConfigError(fmt::format("intc.inputs: {} are too few for {} accelerator pairs (they need {})",
                                      intc_->irq_in.size(), pairs, map::irq::fhg(pairs - 1) + 1));
    iig_irqs_.init(pairs);
    fhg_irqs_.init(pairs);
    std::vector<sc_core::sc_signal<bool>*> line(intc_->irq_in.size(), &low_);
    line[map::irq::dma] = &dma_irq_;
    dma_->irq.bind(dma_irq_);
    tracer.signal(dma_irq_, "irq.dma");
    for (unsigned k = 0; k < pairs; ++k) {
        iigs_[k]->irq.bind(iig_irqs_[k]);
        fhgs_[k]->irq.bind(fhg_irqs_[k]);
        line[map::irq::iig(k)] = &iig_irqs_[k];
        line[map::irq::fhg(k)] = &fhg_irqs_[k];
        tracer.signal(iig_irqs_[k], std::string("irq.") + iigs_[k]->basename());
        tracer.signal(fhg_irqs_[k], std::string("irq.") + fhgs_[k]->basename());
    }
    for (unsigned i = 0; i < intc_->irq_in.size(); ++i) intc_->irq_in[i].bind(*line[i]);
    intc_->irq.bind(cpu_irq_);
    cpu_->irq.bind(cpu_irq_);
    tracer.signal(cpu_irq_, "irq.cpu");
}

uint64_t Soc::bus_transactions() const { return plb1_->tlm_transactions() + plb2_->tlm_transactions(); }

// Every block's statistics under its place in report.json; several pairs are numbered. The
// wiring adds what only it knows: which path the CPU's memory takes, and that port's wait.
void Soc::register_statistics() {
    plb1_->register_statistics(statistics_.scope("buses.plb1"));
    plb2_->register_statistics(statistics_.scope("buses.plb2"));
    if (mci_) mci_->register_statistics(statistics_.scope("mci"));
    memory_->register_statistics(statistics_.scope("memory"));
    const Statistics::Scope cpu = statistics_.scope("cpu");
    cpu_->register_statistics(cpu);
    cpu.text(
        "memory.path", [this] { return cpu_memory_path_; }, "the CPU's way to DDR: mci or plb1");
    cpu.time(
        "memory.ddr_wait_s",
        [this] {
            for (const auto& p : memory_->port_stats())
                if (p.name == cpu_memory_path_) return p.wait;  // the CPU is the only master behind that port
            return sc_core::SC_ZERO_TIME;
        },
        "the CPU's accesses waiting for the DRAM behind the DMA's");
    intc_->register_statistics(statistics_.scope("interrupts"));
    dma_->register_statistics(statistics_.scope("dma"));
    for (size_t k = 0; k < iigs_.size(); ++k) {
        const std::string n = iigs_.size() > 1 ? "." + std::to_string(k) : "";
        iigs_[k]->register_statistics(statistics_.scope("iig" + n));
        fhgs_[k]->register_statistics(statistics_.scope("fhg" + n));
    }
}

}  // namespace surfvp
