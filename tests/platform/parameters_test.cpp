// The parameter table's assumption band: every assumed value has a plausible low and high
// that parse as values of the parameter.
#include <gtest/gtest.h>

#include "platform/scenario/parameters.h"

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
        for (const std::string& v : {p.band.low, p.band.high}) EXPECT_NO_THROW(parse_value(p, v)) << p.key << " = " << v;
    }
    EXPECT_GT(assumed, 40u);
    EXPECT_GE(band_parameters().size(), assumed);  // and a few uncertain sourced ones
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
