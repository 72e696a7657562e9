// The GTKWave save file of a run: groups in the given order, every signal with the format
// its kind asks for, the task filter, and a zoom that fits the whole run in the wave pane.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <string>

#include "models/host/gtkwave_save.h"

namespace surfvp {
namespace {

size_t position(const std::string& text, const std::string& what) {
    const size_t at = text.find(what);
    EXPECT_NE(at, std::string::npos) << what;
    return at;
}

TEST(GtkwaveSave, GroupsFormatsFilterAndZoom) {
    const std::vector<VcdSignal> signals{{"fhg.busy", 1},
                                         {"fhg.maxima_fifo_level", 32},
                                         {"sw.describing_task", 32},
                                         {"plb2.write_busy", 1},
                                         {"zz.other", 8}};
    GtkwaveSave save{
        "/o/trace.vcd", "/o/trace.gtkw", "/o/trace.tasks.txt", 442324645000ull, {{"sw", "Tasks"}, {"fhg", "SSA FHG"}}};
    const std::string s = gtkwave_save(signals, save);
    EXPECT_NE(s.find("[dumpfile] \"/o/trace.vcd\""), std::string::npos);
    EXPECT_NE(s.find("[savefile] \"/o/trace.gtkw\""), std::string::npos);
    // Titled groups first, in their order, then the others as traced.
    EXPECT_LT(position(s, "-Tasks\n"), position(s, "-SSA FHG\n"));
    EXPECT_LT(position(s, "-SSA FHG\n"), position(s, "-plb2\n"));
    EXPECT_LT(position(s, "-plb2\n"), position(s, "-zz\n"));
    EXPECT_NE(s.find("@28\nSystemC.fhg.busy\n"), std::string::npos);  // a wire: binary
    EXPECT_NE(s.find("@8024\nSystemC.fhg.maxima_fifo_level[31:0]\n@20000\n-\n-\n-\n"),
              std::string::npos);  // analog step
    EXPECT_NE(s.find("^1 /o/trace.tasks.txt\n@2024\nSystemC.sw.describing_task[31:0]\n"), std::string::npos);
    EXPECT_NE(s.find("@24\nSystemC.zz.other[7:0]\n"), std::string::npos);
    EXPECT_EQ(gtkwave_task_filter(), "4294967295 none\n");
    // 2^-zoom / 200 time units per pixel (measured with GTKWave 3.3.118): the run spans 860 pixels.
    const double zoom = gtkwave_zoom(save.end_ps);
    EXPECT_NEAR(std::exp2(-zoom) / 200 * 860, double(save.end_ps), 1e-6 * double(save.end_ps));
    char line[32];
    std::snprintf(line, sizeof line, "\n*%.6f -1", zoom);
    EXPECT_NE(s.find(line), std::string::npos) << line;
}

}  // namespace
}  // namespace surfvp
