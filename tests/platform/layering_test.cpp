// The house's layers (docs/architecture.md, "Folder map"): every project include runs down or
// sideways, never up. The chip (platform's scenario, workload, soc, direct, cost, catalog) is built as its own
// library and never includes the application around it (run loop, reports, verdict, sweep,
// tools, CLI); the model contract (models/common) never includes a block; host tooling
// (models/host) includes nothing of the models. A new include that runs up fails here with the
// file and the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;

const fs::path kRoot = SURFVP_SOURCE_DIR;

// Rank of a unit: a file may include a unit of the same or a lower rank. The unit of a file is
// its folder under platform/ (soc.* and address_map.h are units of their own), models/host,
// models/common, another models block, or sw.
const std::map<std::string, int> kRanks = {
    {"models/host", 0},          {"models/common", 1},         {"models/block", 2},      {"sw", 3},
    {"platform/address_map", 4}, {"platform/scenario", 5},     {"platform/workload", 6}, {"platform/soc", 7},
    {"platform/direct", 8},      {"platform/cost", 9},         {"platform/catalog", 10}, {"platform/report", 11},
    {"platform/run", 12},        {"platform/sweep", 13},       {"platform/verdict", 14}, {"platform/compare", 15},
    {"platform/table2", 16},     {"platform/correlation", 17}, {"platform/tools", 18},   {"platform/quality", 19},
    {"platform/cli", 20},
};
constexpr int kLastChipRank = 10;  // platform/catalog: the chip library ends here

// The unit of a path relative to the root ("platform/run/run.cpp" -> "platform/run").
std::string unit_of(const fs::path& relative) {
    const auto first = relative.begin()->string();
    const auto second = std::next(relative.begin())->string();
    if (first == "models") return second == "host" || second == "common" ? "models/" + second : "models/block";
    if (first == "sw") return "sw";
    if (std::distance(relative.begin(), relative.end()) == 2)  // a file at platform/'s top
        return "platform/" + relative.stem().string();
    return "platform/" + second;
}

struct Include {
    fs::path from;  // relative to the root
    int line;
    fs::path to;
};

std::vector<Include> project_includes() {
    static const std::regex include_line(R"re(^\s*#\s*include\s+"((models|sw|platform)/[^"]+)")re");
    std::vector<Include> found;
    for (const char* top : {"models", "sw", "platform"}) {
        for (const auto& entry : fs::recursive_directory_iterator(kRoot / top)) {
            const auto ext = entry.path().extension();
            if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
            std::ifstream in(entry.path());
            std::string text;
            for (int line = 1; std::getline(in, text); ++line) {
                std::smatch m;
                if (std::regex_search(text, m, include_line))
                    found.push_back({fs::relative(entry.path(), kRoot), line, fs::path(m[1].str())});
            }
        }
    }
    return found;
}

int rank_of(const std::string& unit) {
    const auto it = kRanks.find(unit);
    return it == kRanks.end() ? -1 : it->second;
}

}  // namespace

TEST(Layering, EveryFolderHasItsPlace) {
    for (const auto& include : project_includes()) {
        EXPECT_NE(rank_of(unit_of(include.from)), -1)
            << include.from << " is in a folder the layering does not know: give " << unit_of(include.from)
            << " a rank here and a row in docs/architecture.md";
    }
}

TEST(Layering, NoIncludeRunsUp) {
    const auto includes = project_includes();
    ASSERT_GT(includes.size(), 500u) << "the scanner found too few includes to be reading the tree";
    for (const auto& include : includes) {
        const auto from = unit_of(include.from), to = unit_of(include.to);
        EXPECT_LE(rank_of(to), rank_of(from))
            << include.from.string() << ":" << include.line << " includes " << include.to << ": " << from
            << " sits below " << to << " (docs/architecture.md, Folder map)";
    }
}

TEST(Layering, TheChipIncludesNothingOfTheApplication) {
    int chip_includes = 0;
    for (const auto& include : project_includes()) {
        if (rank_of(unit_of(include.from)) > kLastChipRank) continue;
        ++chip_includes;
        EXPECT_LE(rank_of(unit_of(include.to)), kLastChipRank)
            << include.from.string() << ":" << include.line << " is part of the chip and includes " << include.to
            << " of the application";
    }
    EXPECT_GT(chip_includes, 100) << "the chip's files were not found";
}

TEST(Layering, TheUnitsAreTheFoldersOfTheTree) {
    EXPECT_EQ(unit_of("platform/run/run.cpp"), "platform/run");
    EXPECT_EQ(unit_of("platform/soc.h"), "platform/soc");
    EXPECT_EQ(unit_of("platform/address_map.h"), "platform/address_map");
    EXPECT_EQ(unit_of("models/host/worker.h"), "models/host");
    EXPECT_EQ(unit_of("models/fhg/fhg.h"), "models/block");
    EXPECT_EQ(unit_of("sw/surf/surf.h"), "sw");
    EXPECT_LT(rank_of("platform/soc"), rank_of("platform/run"));
}
