// `surfvp export-sequence` through the real binary: the image files with the resource model's
// RAMB36 count, the check of an image read back, and a broken image refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "models/fhg/sequence_cache.h"
#include "models/fhg/fhg.h"
#include "models/fhg/rtl_parameters.h"
#include "models/fhg/sequence_memory.h"

namespace surfvp {
namespace {
using test::fresh_dir;
using test::slurp;
using test::surfvp;

TEST(ExportSequence, WritesTheImageTheCheckAcceptsAndTheModelCounts) {
    const std::string out = fresh_dir("export_sequence");
    const auto r = surfvp("export-sequence --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(slurp(out + "/fhg_sequence.json"));
    const int cycles = nlohmann::json::parse(surfvp("seqgen").out)["cycles_per_block"];
    EXPECT_EQ(j["depth"], cycles);  // the basic script's interval: one word a cycle
    EXPECT_EQ(j["width_bits"], 231);
    EXPECT_EQ(j["ramb36"], 4);  // 231 bits over four 72-bit columns, 512 deep
    EXPECT_EQ(j["fields"].size(), 1u + 4 * (3 + 4) + 18 * 5);
    EXPECT_NE(r.out.find(std::to_string(cycles) + " words x 231 bits in 4 RAMB36"), std::string::npos) << r.out;
    for (const char* file : {"fhg_sequence.coe", "fhg_sequence.mem"}) {
        const auto check = surfvp(std::string("export-sequence --check ") + out + "/" + file);
        EXPECT_EQ(check.exit_code, 0) << check.err;
        EXPECT_NE(check.out.find("the replay checker accepts it"), std::string::npos) << check.out;
    }
    // Another machine's layout does not read it: 6 buses make a 283-bit word.
    const auto other = surfvp("export-sequence --set fhg.read_buses=6 --check " + out + "/fhg_sequence.mem");
    EXPECT_EQ(other.exit_code, 2);
    EXPECT_NE(other.err.find("is not a word of 283 bits (71 hex digits; it has 58)"), std::string::npos) << other.err;
}

// The RTL's parameters come from the configuration: the defaults are what the build verilates
// (tests/CMakeLists.txt prints them from the model's own defaults); a changed width shows.
TEST(ExportSequence, WritesTheRtlParametersOfTheConfiguration) {
    const std::string out = fresh_dir("export_rtl");
    ASSERT_EQ(surfvp("export-sequence --out " + out).exit_code, 0);
    const std::string header = slurp(out + "/fhg_params.vh");
    const Fhg::Params defaults;  // what the build verilates
    EXPECT_EQ(header, fhg::rtl_parameters(defaults.precision, defaults.sequence, defaults.max_width));
    for (const char* line : {"localparam ACC_BITS = 24;", "localparam SEQ_WIDTH = 231;", "localparam WEIGHT = 3318;",
                             "localparam K_BITS = 19;", "        5'd17: det_reciprocal = 19'd12901;"})
        EXPECT_NE(header.find(line), std::string::npos) << line;
    const auto r = surfvp("export-sequence --set 'fhg.accumulator_bits=20 bit' --set fhg.read_buses=6 --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string changed = slurp(out + "/fhg_params.vh");
    EXPECT_NE(changed.find("localparam ACC_BITS = 20;"), std::string::npos);
    EXPECT_NE(changed.find("localparam READ_BUSES = 6;"), std::string::npos);
    const auto x3 = surfvp("export-sequence --set 'fhg.x3_cycles=2 cycles' --out " + out);
    EXPECT_EQ(x3.exit_code, 2);
    EXPECT_NE(x3.err.find("fhg.x3_cycles must be 1 or 3"), std::string::npos) << x3.err;
}

// One bit flipped in the image: the replay names the cycle and the TripleMAC.
TEST(ExportSequence, ABrokenImageIsRefusedNamingTheWordAndTheTripleMac) {
    const std::string out = fresh_dir("export_broken");
    ASSERT_EQ(surfvp("export-sequence --out " + out).exit_code, 0);
    const fhg::SequenceParams p;
    fhg::SequenceImage image = fhg::parse_image(slurp(out + "/fhg_sequence.mem"), fhg::sequence_layout(p));
    const fhg::MemoryField& coefficient = image.layout.field("mac0_coefficient");
    size_t c = 0;  // TripleMAC 0's first value: its coefficient's sign flipped
    while (!fhg::field_value(image.words[c], image.layout.field("mac0_take"))) ++c;
    fhg::set_field(image.words[c], coefficient, fhg::field_value(image.words[c], coefficient) ^ 1);
    const std::string broken = test::write_file(out, "broken.mem", fhg::to_readmemh(image, "broken"));
    const auto r = surfvp("export-sequence --check " + broken);
    EXPECT_EQ(r.exit_code, 2);
    const std::string said = "surfvp: error: --check " + broken +
                             ": the replay fails: TripleMAC 0 does not receive exactly its reads: it misses I(";
    EXPECT_EQ(r.err.substr(0, said.size()), said);
    EXPECT_NE(r.err.find(" and gets I("), std::string::npos) << r.err;  // the same value, the sign flipped
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    const auto missing = surfvp("export-sequence --check " + out + "/none.mem");
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("none.mem: no such file"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace surfvp
