// Inputs a hostile user gives and machines that refuse writes: each ends with a message that
// names the thing and its documented exit code (README: 2 bad input, 4 a refused write), and
// no file is left under a final name half written.
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "cli.h"

namespace surfvp::test {
namespace {
namespace fs = std::filesystem;

const std::string kShort = kOneRun + " --set surf.frames=3 --set surf.width=512 --set surf.height=384 --set budget.fps=0";

TEST(Environment, ValuesThatDoNotFitOrAreNotNumbersAreBadInput) {
    for (const char* set : {"'fhg.recip_shift=4294967306 bit'", "'fhg.x3_cycles=1e30 cycles'", "budget.fps=nan",
                            "budget.fps=inf", "memory.efficiency=-nan"}) {
        const auto r = surfvp("validate " + kBudget + " --set " + set);
        EXPECT_EQ(r.exit_code, 2) << set << ": " << r.err;
        EXPECT_NE(r.err.find("surfvp: error:"), std::string::npos) << set << ": " << r.err;
    }
}

// A file-size limit stands in for a full disk: every write past it fails (EFBIG), as on a
// full disk (ENOSPC), without privileges.
int run_with_file_limit(const std::string& args, unsigned kib, std::string& err) {
    const std::string log = fresh_path("limited.err");
    const std::string command = "bash -c \"trap '' XFSZ; ulimit -f " + std::to_string(kib) + "; exec " +
                                std::string(SURFVP_BINARY) + " " + args + "\" 2>" + log;
    const int status = std::system(command.c_str());
    err = slurp(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Environment, AFullDiskWhileTracingEndsWithItsOwnExitCodeAndNoPartialFile) {
    for (const char* trace : {"perfetto", "vcd"}) {
        const std::string out = fresh_dir(std::string("full_") + trace);
        std::string err;
        EXPECT_EQ(run_with_file_limit("run " + kBudget + " --quiet --trace " + trace + " --out " + out + kShort, 64, err), 4)
            << err;
        EXPECT_NE(err.find("surfvp: cannot write: " + out + "/trace."), std::string::npos) << err;
        for (const auto& f : fs::directory_iterator(out))
            EXPECT_EQ(f.path().filename().string().find("trace."), std::string::npos) << f.path();
    }
}

// Two runs on one folder at once: each trace has a temporary name of its own, so both
// finish and what is left is complete.
TEST(Environment, TwoRunsOnOneFolderDoNotCorruptEachOther) {
    const std::string out = fresh_dir("twice");
    const std::string run = std::string(SURFVP_BINARY) + " run " + kBudget + " --quiet --trace all --out " + out + kShort;
    const int status = std::system(("(" + run + " & " + run + " & wait) 2>/dev/null").c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_NO_THROW(nlohmann::json::parse(slurp(out + "/trace.perfetto.json")));
    EXPECT_NO_THROW(nlohmann::json::parse(slurp(out + "/report.json")));
    for (const auto& f : fs::directory_iterator(out))
        EXPECT_EQ(f.path().string().find("partial"), std::string::npos) << f.path();
    const std::string vcd = slurp(out + "/trace.vcd");
    EXPECT_EQ(vcd.rfind("#") != std::string::npos && vcd.back() == '\n', true);
}

}  // namespace
}  // namespace surfvp::test
