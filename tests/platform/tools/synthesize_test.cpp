// `surfvp synthesize` through the real binary: yosys synthesizes the FHG datapath's Verilog
// part by part for the device's family (Virtex-5), and the resource model's estimate of each
// part is within 20 % of it: its LUTs and flip-flops, its DSP48E and RAMB36 exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "cli.h"

namespace surfvp {
namespace {
using test::slurp;
using test::surfvp;

TEST(Synthesize, TheModelsEstimateOfEachPartIsWithinAFifthOfYosys) {
    // A relative folder (as the default is): yosys runs in its rtl/ and writes beside it.
    const std::string out = "synthesize_" + std::to_string(::getpid());
    std::filesystem::remove_all(out);
    const auto r = surfvp("synthesize --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    struct Remove {
        std::string dir;
        ~Remove() { std::filesystem::remove_all(dir); }
    } remove{out};
    const auto j = nlohmann::json::parse(slurp(out + "/synthesis.json"));
    EXPECT_EQ(j["family"], "xc5v");  // fpga.device XC5VFX70T
    ASSERT_EQ(j["parts"].size(), 4u);
    for (const auto& part : j["parts"]) {
        const auto &y = part["yosys"], &m = part["model"];
        const std::string name = part["part"];
        for (const char* kind : {"luts", "ffs"}) {
            const double synthesized = y[kind], model = m[kind];
            EXPECT_NEAR(model, synthesized, 0.2 * synthesized) << name << " " << kind;
        }
        EXPECT_EQ(y["dsp48e"], m["dsp48e"]) << name;
        // The sequence memory is a ROM to yosys, which drops the bits no word sets (ports a
        // machine never uses): its block RAM is at most the model's, and within one RAMB36.
        EXPECT_LE(y["ramb36"].get<double>(), m["ramb36"].get<double>()) << name;
        EXPECT_GE(y["ramb36"].get<double>(), m["ramb36"].get<double>() - 1) << name;
    }
    EXPECT_GT(j["parts"][0]["yosys"]["luts"].get<double>(), 100);  // a TripleMAC's real logic
    EXPECT_EQ(j["parts"][1]["yosys"]["dsp48e"], 10);               // HessianCalc's products
    EXPECT_EQ(j["parts"][2]["yosys"]["ramb36"], 3);                // the sequence memory: 6 RAMB18
    // The folder holds the configuration's RTL, ready for a simulator or a synthesis tool.
    for (const char* file : {"rtl/fhg_datapath.v", "rtl/sequence_memory.v", "rtl/fhg_params.vh", "rtl/fhg_sequence.mem",
                             "yosys/hessian_calc.log", "synthesis.md"})
        EXPECT_TRUE(std::filesystem::exists(out + "/" + file)) << file;
    EXPECT_NE(slurp(out + "/synthesis.md").find("| HessianCalc | 1 | "), std::string::npos);
}

// The whole line FIFO, on a small machine (two scalar buses: two lanes, 56 BRAMs; about 20 s of
// yosys, where the default takes four minutes): the routing the model adds to the BRAMs comes
// within a fifth of yosys's (measured: 3,944 LUTs and 53 flip-flops, the model 4,189 and 53).
TEST(Synthesize, TheWholeLineFifoIsWithinAFifthOfTheModel) {
    const std::string out = "synthesize_fifo_" + std::to_string(::getpid());
    std::filesystem::remove_all(out);
    const auto r = surfvp(
        "synthesize --whole-fifo --set fhg.bus_word=scalar --set fhg.read_buses=2 "
        "--set fhg.line_fifo=tdp --out " +
        out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(slurp(out + "/synthesis.json"));
    std::filesystem::remove_all(out);
    ASSERT_EQ(j["parts"].size(), 5u);
    const auto& whole = j["parts"][4];
    EXPECT_EQ(whole["part"], "line FIFO, whole");
    const auto &y = whole["yosys"], &m = whole["model"];
    EXPECT_NEAR(m["luts"].get<double>(), y["luts"].get<double>(), 0.2 * y["luts"].get<double>());
    EXPECT_EQ(m["ffs"], y["ffs"]);  // the lanes' registers and the write side's counters, exactly
    EXPECT_EQ(y["ramb36"], 56);
    EXPECT_EQ(y["dsp48e"], 0);
    // The routing is synthesized, so it is not listed as left to the model.
    for (const auto& n : j["not_synthesized"]) EXPECT_EQ(n.get<std::string>().find("routing"), std::string::npos) << n;
}

TEST(Synthesize, AnUnknownFamilyIsBadInput) {
    const std::string out = test::fresh_path("synthesize_bad");
    const auto r = surfvp("synthesize --family xc9 --out " + out);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--family xc9: not a family synth_xilinx maps here: xc5v, xc6s, xc6v or xc7"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace surfvp
