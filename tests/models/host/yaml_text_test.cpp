// YAML text that would hang yaml-cpp 0.7 is refused before it reaches it; other text is
// parsed as yaml-cpp parses it.
#include "models/host/yaml_text.h"

#include <gtest/gtest.h>

namespace surfvp {
namespace {

TEST(YamlText, ACommaWhereANodeBeginsIsFoundWithItsLine) {
    EXPECT_EQ(yaml_hang_line(",: e!Un"), 1u);  // the fuzzer's input
    EXPECT_EQ(yaml_hang_line(" ,:"), 1u);
    EXPECT_EQ(yaml_hang_line("# comment\n\n,"), 3u);
    EXPECT_EQ(yaml_hang_line("%YAML 1.2\n--- ,:"), 2u);
    EXPECT_EQ(yaml_hang_line("a: 1\n---\n,"), 3u);
    EXPECT_EQ(yaml_hang_line("- a\n,"), 2u);
    EXPECT_EQ(yaml_hang_line("# c\r,"), 2u);  // a lone \r breaks the line too
    EXPECT_EQ(yaml_hang_line("\xEF\xBB\xBF,"), 1u);
    // After the node's properties (found by tests/fuzz scenario with seed 2: "!s,et ...").
    for (const char* text : {"!,", "! ,", "!!str ,", "&a ,", "!t,", "&a !t ,", "!<x> ,", "--- !t ,", "- a\n!,"})
        EXPECT_NE(yaml_hang_line(text), 0u) << text;
}

TEST(YamlText, CommasInsideNodesAreLeftToYamlCpp) {
    EXPECT_EQ(yaml_hang_line("a: [1, 2]\nb: 1, 2\nc:\n  - x,\n  ,y: 3\n"), 0u);
    EXPECT_EQ(yaml_hang_line("!t [a, b]\n"), 0u);
    EXPECT_EQ(yaml_hang_line("&a x,y\n"), 0u);
    EXPECT_EQ(load_yaml("a: [1, 2]\nb: 1, 2\n")["b"].as<std::string>(), "1, 2");
    EXPECT_EQ(load_all_yaml("a: 1\n---\nb: 2\n").size(), 2u);
}

TEST(YamlText, RefusalIsAParserExceptionAtTheLine) {
    try {
        load_all_yaml("name: x\n---\n,: e!Un\n");
        ADD_FAILURE() << "no exception";
    } catch (const YAML::ParserException& e) {
        EXPECT_EQ(e.mark.line, 2);
        EXPECT_NE(e.msg.find("a ',' where a node begins"), std::string::npos) << e.msg;
    }
}

// yaml-cpp never returns from a NUL byte followed by a comma (found by the scenario fuzzer).
TEST(YamlText, ANulByteIsRefusedAtItsLine) {
    try {
        load_all_yaml(std::string("name: x\n\0,", 10));
        FAIL() << "a NUL byte was handed to yaml-cpp";
    } catch (const YAML::ParserException& e) {
        EXPECT_EQ(e.mark.line, 1);
        EXPECT_NE(std::string(e.what()).find("NUL"), std::string::npos);
    }
}

// yaml-cpp 0.7 also never returns on a ',' after a complete top-level node, which the ','
// check above does not see (found by the sweep_file fuzzer: '"a21...",eP:'): its parse is
// stopped by the count of its events, at the line where it began repeating.
TEST(YamlText, TextYamlCppWouldNeverFinishIsStoppedAtItsLine) {
    for (const std::string text : {"\"a\",", "'a' ,b", "[a],", "{a: 1},", "- x\n\"a\",", "&x \"a\",", "---\n\"a\" ,"}) {
        try {
            load_all_yaml(text);
            ADD_FAILURE() << "handed to yaml-cpp: " << text;
        } catch (const YAML::ParserException& e) {
            EXPECT_NE(e.msg.find("yaml-cpp would never finish this text"), std::string::npos) << text << ": " << e.msg;
            EXPECT_EQ(e.mark.line, std::count(text.begin(), text.end(), '\n')) << text;
        }
    }
    // Text with many events for its length is still parsed.
    EXPECT_EQ(load_all_yaml("[[[[[[[[]]]]]]]]\n").size(), 1u);
    EXPECT_EQ(load_yaml("{? , ? , a: [&x b, *x, ~, {:}]}").size(), 3u);
    EXPECT_THROW(load_yaml("k: \"a\",b"), YAML::ParserException);  // yaml-cpp's own refusal: "end of map not found"
}

}  // namespace
}  // namespace surfvp
