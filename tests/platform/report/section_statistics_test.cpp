// report.md's sections show statistics only by the registry paths they list: each listed path is
// one the models register (read from a run's legend, report.json's "statistics"), so renaming a
// statistic in a model fails here rather than leaving a blank in the report; and a section
// that reads a statistic it does not list stops with the section and the path named.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <regex>
#include <string>
#include <vector>

#include "cli.h"
#include "platform/report/section_statistics.h"

namespace surfvp::test {
namespace {

// A listed path as a pattern: '*' is any one level.
std::regex pattern_of(const std::string& path) {
    std::string re;
    for (char c : path) re += c == '*' ? std::string("[^.]+") : c == '.' ? std::string("\\.") : std::string(1, c);
    return std::regex(re);
}

std::vector<std::string> registry_of_a_run() {
    const std::string dir = fresh_dir("section_statistics");
    const Cli run = surfvp("run " + kBudget + kOneRun + " --set surf.frames=3 --set budget.fps=0 --out " + dir);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const auto report = nlohmann::ordered_json::parse(slurp(dir + "/report.json"));
    std::vector<std::string> paths;
    for (const auto& [path, about] : report["statistics"].items()) paths.push_back(path);
    return paths;
}

TEST(SectionStatistics, EveryListedStatisticIsOneTheModelsRegister) {
    const std::vector<std::string> registry = registry_of_a_run();
    ASSERT_GT(registry.size(), 100u);
    size_t listed = 0;
    for (const SectionStatistics& s : report_statistics())
        for (const std::string& leaf : s.leaves) {
            ++listed;
            const std::regex re = pattern_of(s.node + "." + leaf);
            const bool registered = std::any_of(registry.begin(), registry.end(),
                                                [&](const std::string& p) { return std::regex_match(p, re); });
            EXPECT_TRUE(registered) << "report.md's section '" << s.section << "' shows " << s.node << "." << leaf
                                    << ", which no model registers";
        }
    EXPECT_GT(listed, 50u);
}

TEST(SectionStatistics, AStatisticASectionDoesNotListIsRefusedByName) {
    const nlohmann::ordered_json fhg = {{"computing_s", 0.5}, {"cycles_per_blok", 3}};
    const Shown shown(fhg, section_statistics("SSA FHG"));
    EXPECT_DOUBLE_EQ(shown.number("computing_s"), 0.5);
    EXPECT_TRUE(shown["errors"].is_null());  // listed, absent from this report: null
    try {
        (void)shown["cycles_per_blok"];
        FAIL() << "an unlisted statistic was read";
    } catch (const std::logic_error& e) {
        EXPECT_NE(std::string(e.what()).find("'SSA FHG' shows fhg.cycles_per_blok"), std::string::npos) << e.what();
    }
}

TEST(SectionStatistics, InstancesAreReadUnderTheirOwnListedLeaves) {
    const nlohmann::ordered_json bus = {{"masters", {{"cpu", {{"bursts", 7}}}, {"dma", {{"bursts", 2}}}}}};
    const Shown shown(bus, section_statistics("Buses"));
    const auto masters = shown.each("masters");
    ASSERT_EQ(masters.size(), 2u);
    EXPECT_EQ(masters[0].first, "cpu");
    EXPECT_EQ(masters[0].second.count("bursts"), 7u);
    EXPECT_EQ(masters[1].second.count("bursts"), 2u);
    EXPECT_THROW((void)masters[0].second["width_bits"], std::logic_error);  // a bus's leaf, not a master's
}

}  // namespace
}  // namespace surfvp::test
