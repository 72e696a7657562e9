// The parameter table's assumption band: every assumed value has a plausible low and high
// that parse as values of the parameter.
#include <gtest/gtest.h>

#include "platform/scenario/config.h"
#include "platform/scenario/parameters.h"
#include "platform/soc.h"

namespace surfvp {
namespace {

TEST(Parameters, EveryAssumptionHasABandThatParses) {
    size_t assumed = 0;
    for (const ParamSpec& p : parameter_table()) {
        if (p.source.rfind("[A", 0) == 0) {
            ++assumed;
            EXPECT_FALSE(p.band.low.empty()) << p.key << " is assumed but has no band";
        }
        if (p.band.low.empty()) continue;
        EXPECT_FALSE(p.band.high.empty()) << p.key;
        EXPECT_FALSE(p.band.why.empty()) << p.key;
        for (const std::string& v : {p.band.low, p.band.high})
            EXPECT_NO_THROW(parse_value(p, v)) << p.key << " = " << v;
    }
    EXPECT_GT(assumed, 40u);
    EXPECT_GE(band_parameters().size(), assumed);  // and a few uncertain sourced ones
}

// A block's declaration sets its Params field: plain, nested, enum and on/off fields, and
// the register latency in the cycles of the bus the wiring puts the block on.
TEST(Parameters, ABlockDeclarationSetsItsParamsField) {
    Config c;
    c.set("fhg.maxima_fifo_depth", "8", "test");
    c.set("fhg.read_buses", "6", "test");
    c.set("fhg.bus_word", "pair", "test");
    c.set("fhg.reuse", "off", "test");
    c.set("fhg.det_bits", "16 bit", "test");
    c.set("fhg.clock", "125 MHz", "test");
    c.set("fhg.register_latency", "3 cycles", "test");
    c.set("plb1.clock", "50 MHz", "test");
    const Fhg::Params p = fhg_params(c);
    EXPECT_EQ(p.maxima_fifo_depth, 8u);
    EXPECT_EQ(p.sequence.read_buses, 6u);
    EXPECT_EQ(p.sequence.bus_word, fhg::BusWord::pair);
    EXPECT_FALSE(p.sequence.reuse);
    EXPECT_EQ(p.precision.det_bits, 16u);
    EXPECT_DOUBLE_EQ(p.clock.hz, 125e6);
    EXPECT_EQ(p.registers.latency().ps, 60000u);  // 3 cycles of 50 MHz
    c.set("plb2.arbitration", "fixed_priority", "test");
    c.set("memory.efficiency", "0.6", "test");
    c.set("cpu.quantum", "2 us", "test");
    EXPECT_EQ(PlbBus::Params(plb_declarations()[1].table.make(c)).arbitration, PlbBus::Arbitration::fixed_priority);
    EXPECT_DOUBLE_EQ(DdrMemory::parameter_table().make(c).efficiency, 0.6);
    EXPECT_EQ(Ppc440::parameter_table().make(c).quantum.ps, 2000000u);
}

// The blocks' own defaults (their Params structs, which tests and tools use directly) agree
// with their declarations.
TEST(Parameters, BlockDefaultsAgreeWithTheirDeclarations) {
    const Config c;
    const Fhg::Params made = fhg_params(c), plain;
    EXPECT_EQ(made.maxima_fifo_depth, plain.maxima_fifo_depth);
    EXPECT_EQ(made.sequence.fifo_lines, plain.sequence.fifo_lines);
    EXPECT_EQ(made.precision.det_frac_bits, plain.precision.det_frac_bits);
    EXPECT_EQ(made.pipeline_latency_cycles, plain.pipeline_latency_cycles);
    EXPECT_DOUBLE_EQ(made.clock.hz, plain.clock.hz);
    const Iig::Params iig = iig_params(c), iig_plain;
    EXPECT_EQ(iig.sum_bits, iig_plain.sum_bits);
    EXPECT_EQ(iig.line_buffers, iig_plain.line_buffers);
    const DdrMemory::Params ddr = DdrMemory::parameter_table().make(c), ddr_plain;
    EXPECT_EQ(ddr.latency_cycles, ddr_plain.latency_cycles);
    EXPECT_EQ(ddr.size.n, ddr_plain.size.n);
}

TEST(Parameters, SimulationSettingsAreNotAssumptions) {
    for (const char* key : {"cpu.quantum", "run.dma_granularity", "run.max_time", "fhg.sequence_attempts"}) {
        const ParamSpec* p = find_parameter(key);
        ASSERT_NE(p, nullptr) << key;
        EXPECT_EQ(p->source.rfind("[-]", 0), 0u) << key << ": " << p->source;
        EXPECT_TRUE(p->band.low.empty()) << key;
    }
}

}  // namespace
}  // namespace surfvp
