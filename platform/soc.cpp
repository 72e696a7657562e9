#include "soc.h"

#include "address_map.h"

namespace surfvp {
namespace {

PlbBus::Params plb_params(const Config& c, const std::string& bus) {
    PlbBus::Params p;
    p.clock = c.frequency(bus + ".clock");
    p.width_bits = c.bits(bus + ".width");
    p.max_burst_beats = c.beats(bus + ".max_burst");
    p.arbitration_cycles = static_cast<unsigned>(c.cycles(bus + ".arbitration_latency"));
    p.address_cycles = static_cast<unsigned>(c.cycles(bus + ".address_latency"));
    p.arbitration = c.choice(bus + ".arbitration") == "fixed_priority" ? PlbBus::Arbitration::fixed_priority
                                                                       : PlbBus::Arbitration::round_robin;
    if (p.width_bits != 32 && p.width_bits != 64 && p.width_bits != 128)
        throw ConfigError(bus + ".width: a PLB is 32, 64 or 128 bit wide");
    return p;
}

DdrMemory::Params memory_params(const Config& c) {
    DdrMemory::Params p;
    p.size = c.bytes("memory.size");
    p.clock = c.frequency("memory.clock");
    p.width_bits = c.bits("memory.width");
    p.transfers_per_clock = static_cast<unsigned>(c.count("memory.transfers_per_clock"));
    p.efficiency = c.real("memory.efficiency");
    p.latency_cycles = static_cast<unsigned>(c.cycles("memory.latency"));
    return p;
}

nlohmann::ordered_json seconds(const sc_core::sc_time& t) { return t.to_seconds(); }

double share(const sc_core::sc_time& part, const sc_core::sc_time& whole) {
    return whole > sc_core::SC_ZERO_TIME ? part.to_seconds() / whole.to_seconds() : 0.0;
}

nlohmann::ordered_json bus_report(const PlbBus& bus, const sc_core::sc_time& elapsed) {
    nlohmann::ordered_json masters = nlohmann::ordered_json::object();
    for (const auto& m : bus.master_stats())
        masters[m.name] = {{"transactions", m.transactions}, {"bytes_read", m.bytes_read},
                           {"bytes_written", m.bytes_written}, {"errors", m.errors},
                           {"busy_s", seconds(m.busy)}, {"wait_s", seconds(m.wait)}};
    const auto& p = bus.params();
    return {{"clock_hz", p.clock.hz},
            {"width_bits", p.width_bits},
            {"read", {{"transactions", bus.read_stats().transactions}, {"bytes", bus.read_stats().bytes},
                      {"busy_s", seconds(bus.read_stats().busy)}, {"utilisation", share(bus.read_stats().busy, elapsed)}}},
            {"write", {{"transactions", bus.write_stats().transactions}, {"bytes", bus.write_stats().bytes},
                       {"busy_s", seconds(bus.write_stats().busy)}, {"utilisation", share(bus.write_stats().busy, elapsed)}}},
            {"decode_errors", bus.decode_errors()},
            {"masters", masters}};
}

}  // namespace

Soc::Soc(const Config& c, Tracer& tracer) : workload_(make_workload(c)) {
    memory_ = std::make_unique<DdrMemory>("memory", memory_params(c));
    plb1_ = std::make_unique<PlbBus>("plb1", plb_params(c, "plb1"), tracer);
    plb2_ = std::make_unique<PlbBus>("plb2", plb_params(c, "plb2"), tracer);
    intc_ = std::make_unique<Intc>("intc", Intc::Params{static_cast<unsigned>(c.count("intc.inputs"))}, tracer);
    dma_ = std::make_unique<Dma>("dma", Dma::Params{c.beats("dma.burst"), c.bits("plb2.width")}, tracer);
    Ppc440::Params cpu;
    cpu.clock = c.frequency("cpu.clock");
    cpu.quantum = c.duration("cpu.quantum");
    cpu.line_bytes = static_cast<unsigned>(c.bytes("cpu.cache_line").n);
    cpu_ = std::make_unique<Ppc440>("cpu", cpu, workload_->software(), tracer);

    // PLB1: the CPU's MPLB; DDR, the INTC and the register slaves.
    plb1_->connect_master(cpu_->bus, "cpu");
    plb1_->slaves.bind(memory_->ports);
    memory_->name_port("plb1");
    plb1_->slaves.bind(intc_->regs);
    plb1_->slaves.bind(dma_->regs);
    plb1_->map(map::ddr.base, memory_params(c).size.n, 0, map::ddr.name);
    plb1_->map(map::intc.base, map::intc.size, 1, map::intc.name);
    plb1_->map(map::dma.base, map::dma.size, 2, map::dma.name);

    // PLB2: the DMA masters to DDR.
    plb2_->connect_master(dma_->mplb, "dma");
    plb2_->slaves.bind(memory_->ports);
    memory_->name_port("plb2");
    plb2_->map(map::ddr.base, memory_params(c).size.n, 0, map::ddr.name);

    // Interrupts: block lines into the INTC, the INTC into the CPU; unused inputs held low.
    if (map::irq::dma >= intc_->irq_in.size()) throw ConfigError("intc.inputs: too few for the DMA's interrupt line");
    dma_->irq.bind(dma_irq_);
    for (unsigned i = 0; i < intc_->irq_in.size(); ++i) intc_->irq_in[i].bind(i == map::irq::dma ? dma_irq_ : low_);
    intc_->irq.bind(cpu_irq_);
    cpu_->irq.bind(cpu_irq_);
    tracer.signal(dma_irq_, "irq.dma");
    tracer.signal(cpu_irq_, "irq.cpu");
}

uint64_t Soc::bus_transactions() const {
    return plb1_->read_stats().transactions + plb1_->write_stats().transactions + plb2_->read_stats().transactions +
           plb2_->write_stats().transactions;
}

nlohmann::ordered_json Soc::report(const sc_core::sc_time& elapsed) const {
    nlohmann::ordered_json ports = nlohmann::ordered_json::object();
    uint64_t bytes_read = 0, bytes_written = 0;
    for (const auto& p : memory_->port_stats()) {
        ports[p.name] = {{"reads", p.reads}, {"writes", p.writes}, {"bytes_read", p.bytes_read},
                         {"bytes_written", p.bytes_written}, {"wait_s", seconds(p.wait)}};
        bytes_read += p.bytes_read;
        bytes_written += p.bytes_written;
    }
    const auto& s = cpu_->stats();
    return {{"buses", {{"plb1", bus_report(*plb1_, elapsed)}, {"plb2", bus_report(*plb2_, elapsed)}}},
            {"memory", {{"bytes_read", bytes_read}, {"bytes_written", bytes_written},
                        {"busy_s", seconds(memory_->busy())}, {"utilisation", share(memory_->busy(), elapsed)},
                        {"note", "bus-port traffic; the CPU's DMI accesses are counted under cpu"},
                        {"ports", ports}}},
            {"cpu", {{"mmio_reads", s.mmio_reads}, {"mmio_writes", s.mmio_writes},
                     {"memory_bytes_read", s.bytes_read}, {"memory_bytes_written", s.bytes_written},
                     {"cycles_consumed", s.cycles_consumed}, {"irq_waits", s.irq_waits},
                     {"irq_wait_s", seconds(s.irq_wait_time)}}},
            {"interrupts", {{"raised", intc_->interrupts_raised()}}},
            {"dma", {{"copies", dma_->copies()}, {"bytes_copied", dma_->bytes_copied()}}}};
}

}  // namespace surfvp
