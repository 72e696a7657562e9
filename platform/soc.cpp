#include "platform/soc.h"

#include <cmath>
#include <fmt/format.h>

#include "platform/address_map.h"
#include "models/dma/dma_regs.h"
#include "models/fhg/fhg_regs.h"
#include "models/iig/iig_regs.h"
#include "models/intc/intc_regs.h"
#include "platform/tools/seqgen.h"

namespace surfvp {
namespace {

PlbBus::Params plb_params(const Config& c, const std::string& bus) {
    for (const PlbDeclaration& d : plb_declarations()) {
        if (d.bus != bus) continue;
        PlbBus::Params p = d.table.make(c);
        p.series_bin = c.duration("run.series_bin");
        if (p.width_bits != 32 && p.width_bits != 64 && p.width_bits != 128)
            throw ConfigError(bus + ".width: a PLB is 32, 64 or 128 bit wide");
        return p;
    }
    throw std::logic_error("no PLB named " + bus);
}

DdrMemory::Params memory_params(const Config& c) {
    DdrMemory::Params p = DdrMemory::parameter_table().make(c);
    p.series_bin = c.duration("run.series_bin");
    p.populate_ahead = c.choice("run.parallel") == "on";
    return p;
}
MciLink::Params mci_params(const Config& c) { return MciLink::parameter_table().make(c); }

bool cpu_memory_on_plb1(const Config& c) { return c.choice("cpu.memory_path") == "plb1"; }

// The register slaves are on PLB1: their answers are in its cycles.
template <typename Params>
Params on_plb1(Params p, const Config& c) {
    p.registers.bus_clock = c.frequency("plb1.clock");
    return p;
}

// One TLM transaction per line (fast) or per burst (finest contention).
uint64_t dma_transaction_bytes(const Config& c, unsigned burst_beats) {
    return c.choice("run.dma_granularity") == "burst" ? uint64_t(burst_beats) * c.bits("plb2.width") / 8 : 0;
}

}  // namespace

std::vector<MappedRegisters> chip_registers() {
    auto at = [](const map::Region& r, const char* bus) { return fmt::format("Its window is {:#010x} on {}", r.base, bus); };
    const std::string pairs = fmt::format(", pair k at + k x {:#x}", map::kAcceleratorStride);
    return {{&iig::table(), at(map::iig, "PLB1") + pairs},
            {&fhg_regs::table(), at(map::fhg, "PLB1") + pairs},
            {&intc::table(), at(map::intc, "PLB1") + fmt::format(" (inputs: DMA {}, IIG k {} + 2k, FHG k {} + 2k)", map::irq::dma,
                                                                   map::irq::iig(0), map::irq::fhg(0))},
            {&dma::table(), at(map::dma, "PLB1")}};
}

FillTiming uncontended_fills(const Config& c) {
    const uint64_t line = c.bytes("cpu.cache_line").n;
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
    p.parallel = c.choice("run.parallel") == "on";
    p.series_bin = c.duration("run.series_bin");
    p.dma_transaction_bytes = dma_transaction_bytes(c, p.burst_beats);
    return p;
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
    const unsigned pairs = unsigned(c.count("soc.accelerators"));
    // The VCD's groups in GTKWave, in the order of the paper's Fig. 3.
    std::vector<std::pair<std::string, std::string>> titles{{"sw", "Tasks (libSSA2)"}, {"irq", "Interrupts"}, {"cpu", "PPC440"}};
    for (unsigned k = 0; k < pairs; ++k) {
        const std::string suffix = pairs > 1 ? std::to_string(k) : "";
        titles.emplace_back("iig" + suffix, "SSA IIG" + (suffix.empty() ? "" : " " + suffix));
        titles.emplace_back("fhg" + suffix, "SSA FHG" + (suffix.empty() ? "" : " " + suffix));
    }
    titles.insert(titles.end(), {{"plb1", "PLB1 (CPU, registers)"}, {"plb2", "PLB2 (DMA traffic)"}, {"dma", "Test DMA"}});
    tracer.group_titles(std::move(titles));
    cpu_memory_path_ = c.choice("cpu.memory_path");
    memory_ = std::make_unique<DdrMemory>("memory", memory_params(c));
    plb1_ = std::make_unique<PlbBus>("plb1", plb_params(c, "plb1"), tracer);
    plb2_ = std::make_unique<PlbBus>("plb2", plb_params(c, "plb2"), tracer);
    if (!cpu_memory_on_plb1(c)) mci_ = std::make_unique<MciLink>("mci", mci_params(c));
    intc_ = std::make_unique<Intc>("intc", on_plb1(Intc::parameter_table().make(c), c), tracer);
    Dma::Params dma = on_plb1(Dma::parameter_table().make(c), c);
    dma.bus_width_bits = c.bits("plb2.width");
    dma_ = std::make_unique<Dma>("dma", dma, tracer);
    for (unsigned k = 0; k < pairs; ++k) {
        const std::string suffix = pairs > 1 ? std::to_string(k) : "";
        iigs_.push_back(std::make_unique<Iig>(("iig" + suffix).c_str(), iig_params(c), tracer));
        fhgs_.push_back(std::make_unique<Fhg>(("fhg" + suffix).c_str(), fhg_params(c), tracer));
    }
    Ppc440::Params cpu = Ppc440::parameter_table().make(c);
    cpu.critical_word_lead = Duration{uncontended_fills(c).critical_word_lead.value()};
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
    plb2_->connect_master(dma_->mplb, "dma", c.beats("dma.burst"));
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
    cpu.text("memory.path", [this] { return cpu_memory_path_; }, "the CPU's way to DDR: mci or plb1");
    cpu.time("memory.ddr_wait_s", [this] {
        for (const auto& p : memory_->port_stats())
            if (p.name == cpu_memory_path_) return p.wait;  // the CPU is the only master behind that port
        return sc_core::SC_ZERO_TIME;
    }, "the CPU's accesses waiting for the DRAM behind the DMA's");
    intc_->register_statistics(statistics_.scope("interrupts"));
    dma_->register_statistics(statistics_.scope("dma"));
    for (size_t k = 0; k < iigs_.size(); ++k) {
        const std::string n = iigs_.size() > 1 ? "." + std::to_string(k) : "";
        iigs_[k]->register_statistics(statistics_.scope("iig" + n));
        fhgs_[k]->register_statistics(statistics_.scope("fhg" + n));
    }
}

}  // namespace surfvp
