// The VCD writer: SystemC's layout, and per time step the values at its end that differ from
// the last written, in the order the signals were added.
#include <gtest/gtest.h>
#include <string>

#include "models/common/vcd_writer.h"
#include "platform/cli.h"
#include "platform/vcd_reader.h"

namespace surfvp {
namespace {

using test::slurp;

// A file in a fresh folder of this test process.
std::string temp_path(const std::string& name) { return test::fresh_dir("vcd_writer") + "/" + name; }

// What follows the $date block (the only part that depends on when it was written).
std::string after_date(const std::string& vcd) { return vcd.substr(vcd.find("$end") + 4); }

TEST(VcdWriter, WritesScopesInNameOrderAndEachStepsChangesInTheOrderAdded) {
    const std::string path = temp_path("layout.vcd");
    VcdWriter vcd(path);
    const int busy = vcd.add("plb2.busy", 1, 0);
    const int level = vcd.add("fhg.level", 32, 5);
    const int task = vcd.add("sw.task", 32, 0xffffffffu);  // -1 as a 32-bit word
    const int irq = vcd.add("irq.fhg", 1, 0);
    vcd.change(irq, 1, 0);  // at time 0: part of the initial values
    vcd.change(level, 6, 1000);
    vcd.change(busy, 1, 1000);  // the same step: written before level, which was added later
    vcd.change(task, 3, 2000);
    vcd.change(task, 4, 2000);  // the step's last value counts
    vcd.change(busy, 0, 3000);
    vcd.change(busy, 1, 3000);  // back to the written value in the same step: nothing to write
    vcd.change(level, 0, 4000);
    ASSERT_TRUE(vcd.close(5000));
    EXPECT_EQ(after_date(slurp(path)),
              "\n\n$version\n surfvp\n$end\n\n$timescale\n     1 ps\n$end\n\n"
              "$scope module SystemC $end\n"
              "$scope module fhg $end\n$var wire   32  aaaab  level [31:0]  $end\n$upscope $end\n"
              "$scope module irq $end\n$var wire    1  aaaad  fhg       $end\n$upscope $end\n"
              "$scope module plb2 $end\n$var wire    1  aaaaa  busy       $end\n$upscope $end\n"
              "$scope module sw $end\n$var wire   32  aaaac  task [31:0]  $end\n$upscope $end\n"
              "$upscope $end\n$enddefinitions  $end\n\n"
              "$comment\nAll initial values are dumped below at time 0 sec = 0 timescale units.\n$end\n\n"
              "$dumpvars\n0aaaaa\nb101 aaaab\nb11111111111111111111111111111111 aaaac\n1aaaad\n$end\n"
              "\n#1000\n1aaaaa\nb110 aaaab\n"
              "\n#2000\nb100 aaaac\n"
              "\n#4000\nb0 aaaab\n"
              "\n#5000\n");
    const auto read = test::Vcd::read(path);
    EXPECT_EQ(read.timescale, "1ps");
    EXPECT_EQ(read.rises("plb2.busy"), 1u);
    EXPECT_EQ(read.changes.at("fhg.level").back(), (std::pair<uint64_t, std::string>{4000, "0"}));
}

// Identifiers run past 26 signals into the next letter, as SystemC's do.
TEST(VcdWriter, TheTwentySeventhSignalIsAaaba) {
    const std::string path = temp_path("many.vcd");
    VcdWriter vcd(path);
    for (int i = 0; i < 27; ++i) vcd.add("s.x" + std::to_string(i), 1, 0);
    ASSERT_TRUE(vcd.close(10));
    const std::string text = slurp(path);
    EXPECT_NE(text.find("$var wire    1  aaaaz  x25       $end"), std::string::npos) << text;
    EXPECT_NE(text.find("$var wire    1  aaaba  x26       $end"), std::string::npos) << text;
}

// A full disk: close() says the file is not whole.
TEST(VcdWriter, AFailedWriteIsReportedAtClose) {
    VcdWriter vcd("/dev/full");
    const int s = vcd.add("a.b", 1, 0);
    for (uint64_t t = 1; t < 100000; ++t) vcd.change(s, t & 1, t);
    EXPECT_FALSE(vcd.close(100000));
}

TEST(VcdWriter, AFolderItCannotWriteIsAnError) {
    EXPECT_THROW(VcdWriter("/nonexistent/dir/trace.vcd"), std::runtime_error);
}

}  // namespace
}  // namespace surfvp
