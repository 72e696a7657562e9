// The docs stand on their own: no file cites a note the project does not ship, every parameter
// has its row in docs/sources.md, every cited anchor of sources.md or architecture.md exists,
// and the figures README.md states about the default scenario are the ones it gives now.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"
#include "platform/scenario/parameters.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

const fs::path kRoot = SURFVP_SOURCE_DIR;

// Every text file of what the project ships (binary files, those with a NUL, are skipped).
std::vector<fs::path> shipped_files() {
    std::vector<fs::path> files{kRoot / "README.md"};
    for (const char* dir : {"docs", "models", "sw", "platform", "scenarios", "scripts", "tests", "traces"}) {
        if (!fs::exists(kRoot / dir)) continue;
        for (const auto& e : fs::recursive_directory_iterator(kRoot / dir))
            if (e.is_regular_file() && e.file_size() < (4u << 20)) files.push_back(e.path());
    }
    std::vector<fs::path> text;
    for (const fs::path& f : files)
        if (test::slurp(f.string()).find('\0') == std::string::npos) text.push_back(f);
    return text;
}

std::string in_tree(const fs::path& p) { return fs::relative(p, kRoot).generic_string(); }

// The anchors GitHub gives a Markdown file's headings: lower case, punctuation dropped, spaces
// to hyphens, a repeated slug numbered -1, -2...
std::set<std::string> heading_anchors(const std::string& markdown) {
    std::set<std::string> anchors;
    std::map<std::string, int> seen;
    std::istringstream in(markdown);
    bool fenced = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("```", 0) == 0) fenced = !fenced;
        if (fenced || line.empty() || line[0] != '#') continue;
        const size_t text = line.find_first_not_of('#');
        if (text == std::string::npos || line[text] != ' ') continue;
        std::string slug;
        for (char c : line.substr(text + 1)) {
            const unsigned char u = static_cast<unsigned char>(c);
            if (std::isalnum(u) || c == '-' || c == '_' || u >= 0x80)
                slug += static_cast<char>(std::tolower(u));
            else if (c == ' ')
                slug += '-';
        }
        const int n = seen[slug]++;
        anchors.insert(n == 0 ? slug : slug + "-" + std::to_string(n));
    }
    return anchors;
}

TEST(Docs, NoFileCitesANoteTheProjectDoesNotShip) {
    // Spelt in pieces, so that this file does not match itself.
    const std::vector<std::string> unshipped = {std::string("PLATFORM") + "_FACTS", std::string("DESIGN") + ".md",
                                                std::string("DESIGN") + " principle", std::string("STYLE") + ".md",
                                                std::string("../") + "shared"};
    const fs::path self = fs::path(__FILE__).filename();
    size_t checked = 0;
    for (const fs::path& f : shipped_files()) {
        if (f.filename() == self) continue;
        ++checked;
        const std::string text = test::slurp(f.string());
        for (const std::string& cite : unshipped)
            EXPECT_EQ(text.find(cite), std::string::npos)
                << in_tree(f) << " cites " << cite << ", which users do not have: cite docs/sources.md#... "
                << "or docs/architecture.md#principles, or state the fact";
    }
    EXPECT_GT(checked, 100u);
}

TEST(Docs, EveryParameterHasItsRowInSources) {
    const std::string sources = test::slurp((kRoot / "docs/sources.md").string());
    ASSERT_FALSE(sources.empty());
    for (const ParamSpec& spec : parameter_table()) {
        const std::string row = "| `" + spec.key + "` | `" + spec.default_value + "` | ";
        const size_t at = sources.find(row);
        if (at == std::string::npos) {
            ADD_FAILURE() << "docs/sources.md has no row `" << row << "...` for " << spec.key << " (default "
                          << spec.default_value << "): add one under its area";
            continue;
        }
        // The tag: the source text's leading [S], [D], [A], [-] (or [S/proxy]).
        const std::string tag = spec.source.substr(0, spec.source.find(']') + 1);
        EXPECT_EQ(sources.compare(at + row.size(), tag.size(), tag), 0)
            << "docs/sources.md gives " << spec.key << " another tag than its declaration's " << tag;
    }
}

TEST(Docs, EveryCitedAnchorIsAHeading) {
    const std::map<std::string, std::set<std::string>> anchors = {
        {"sources.md", heading_anchors(test::slurp((kRoot / "docs/sources.md").string()))},
        {"architecture.md", heading_anchors(test::slurp((kRoot / "docs/architecture.md").string()))}};
    ASSERT_TRUE(anchors.at("sources.md").count("arithmetic"));
    ASSERT_TRUE(anchors.at("architecture.md").count("principles"));
    // docs/sources.md#plb, sources.md#plb, ../sources.md#plb, and in-page links of those two files.
    const std::regex cite(R"((?:^|[^A-Za-z0-9_.-])(?:\.\./)*(?:docs/)?(sources|architecture)\.md#([A-Za-z0-9_-]+))");
    const std::regex self_link(R"(\]\(#([A-Za-z0-9_-]+)\))");
    size_t cites = 0;
    for (const fs::path& f : shipped_files()) {
        const std::string text = test::slurp(f.string());
        for (auto m = std::sregex_iterator(text.begin(), text.end(), cite); m != std::sregex_iterator(); ++m) {
            ++cites;
            EXPECT_TRUE(anchors.at((*m)[1].str() + ".md").count((*m)[2].str()))
                << in_tree(f) << " cites " << (*m)[1] << ".md#" << (*m)[2] << ", which is no heading there";
        }
        const std::string name = in_tree(f);
        if (name != "docs/sources.md" && name != "docs/architecture.md") continue;
        for (auto m = std::sregex_iterator(text.begin(), text.end(), self_link); m != std::sregex_iterator(); ++m)
            EXPECT_TRUE(anchors.at(f.filename().string()).count((*m)[1].str()))
                << name << " links to #" << (*m)[1] << ", which is no heading there";
    }
    EXPECT_GT(cites, 20u);
}

// README.md's sentence on the default scenario's Correlation table: its frame rate, the basic
// script's overhead and the watts, against a run of that scenario (one run, ~2 s).
TEST(Docs, ReadmeFiguresOfTheDefaultScenarioAreCurrent) {
    const std::string readme = test::slurp((kRoot / "README.md").string());
    std::smatch m;
    ASSERT_TRUE(
        std::regex_search(readme, m,
                          std::regex(R"(\*\*Correlation\*\* table: ([0-9.]+) frames/s[^%]*?a basic script ([0-9.]+) %)"
                                     R"([^W]*?([0-9.]+) W against)")))
        << "README.md no longer states the default scenario's frames/s, basic script and watts in the form this "
           "test reads";
    const std::string fps = m[1], overhead = m[2], watts = m[3];

    const std::string out = test::fresh_dir("docs_readme");
    const auto r = test::surfvp("run " + test::kBudget + test::kOneRun + " --trace none --quiet --out " + out);
    ASSERT_LE(r.exit_code, 1) << r.err;
    const Json j = Json::parse(test::slurp(out + "/report.json"));

    // Each figure as README.md rounds it: as many decimals as it shows.
    const auto as_shown = [](double value, const std::string& shown) {
        const size_t dot = shown.find('.');
        const int decimals = dot == std::string::npos ? 0 : int(shown.size() - dot - 1);
        char text[64];
        std::snprintf(text, sizeof text, "%.*f", decimals, value);
        return std::string(text);
    };
    EXPECT_EQ(as_shown(j["throughput_fps"].get<double>(), fps), fps) << "README.md's frames/s is stale";
    EXPECT_EQ(as_shown(100 * j["fhg"]["schedules"]["basic"]["overhead"].get<double>(), overhead), overhead)
        << "README.md's basic-script overhead is stale";
    EXPECT_EQ(as_shown(j["power"]["watts"].get<double>(), watts), watts) << "README.md's watts are stale";
}

}  // namespace
}  // namespace surfvp
