// Same scenario, same bytes out: the budget scenario (its verdict's re-simulations included)
// run twice gives the same report.json without its wall-clock fields, the same report.md
// without its wall-clock rows, and the same VCD (without its $date) and Perfetto trace. The
// verdict's joint sample is cut from 200 points to 20: every step of the band still runs (the
// sample, its percentiles and indices, the tornado), at a third of the time.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli.h"

namespace surfvp::test {
namespace {

// report.json less the fields it names as wall-clock ones.
std::string without_wall_clock(const std::string& text) {
    nlohmann::ordered_json r = nlohmann::ordered_json::parse(text);
    const auto fields = r["wall_clock_fields"];  // a copy: erasing moves the object's members
    for (const auto& field : fields) r.erase(field.get<std::string>());
    return r.dump(1);
}

std::string without_lines_containing(const std::string& text, const std::string& word) {
    std::istringstream in(text);
    std::string kept;
    for (std::string line; std::getline(in, line);)
        if (line.find(word) == std::string::npos) kept += line + "\n";
    return kept;
}

// The VCD's $date block is the wall clock at the start.
std::string without_date(const std::string& vcd) {
    const size_t begin = vcd.find("$date"), end = vcd.find("$end", begin);
    return begin == std::string::npos ? vcd : vcd.substr(0, begin) + vcd.substr(end + 4);
}

TEST(Determinism, TheBudgetScenarioTwiceGivesTheSameBytes) {
    std::string dirs[2];
    for (int i = 0; i < 2; ++i) {
        dirs[i] = fresh_dir("rerun_" + std::to_string(i));
        const auto r = surfvp("run " + kBudget + " --quiet --trace all --set verdict.samples=20 --out " + dirs[i]);
        ASSERT_EQ(r.exit_code, 1) << r.err;  // the budget is missed at the defaults
    }
    const std::string json[2] = {slurp(dirs[0] + "/report.json"), slurp(dirs[1] + "/report.json")};
    EXPECT_NE(json[0], json[1]);                                          // the wall clock differs...
    EXPECT_EQ(without_wall_clock(json[0]), without_wall_clock(json[1]));  // ...and nothing else
    EXPECT_EQ(without_lines_containing(slurp(dirs[0] + "/report.md"), "wall"),
              without_lines_containing(slurp(dirs[1] + "/report.md"), "wall"));
    const std::string vcd = slurp(dirs[0] + "/trace.vcd");
    EXPECT_GT(vcd.size(), 1000000u);
    EXPECT_EQ(without_date(vcd), without_date(slurp(dirs[1] + "/trace.vcd")));
    const std::string perfetto = slurp(dirs[0] + "/trace.perfetto.json");
    EXPECT_GT(perfetto.size(), 1000000u);
    EXPECT_EQ(perfetto, slurp(dirs[1] + "/trace.perfetto.json"));
    for (const char* f : {"frames.csv", "config.yaml", "tornado.svg", "keypoints/frame_0019.surf"})
        EXPECT_EQ(slurp(dirs[0] + "/" + f), slurp(dirs[1] + "/" + f)) << f;
}

}  // namespace
}  // namespace surfvp::test
