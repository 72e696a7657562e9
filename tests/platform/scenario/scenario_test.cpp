// Scenario loading: values with units and their origins, overrides, and each kind of
// validation error named with file, line and key.
#include <gtest/gtest.h>

#include "cli.h"
#include "platform/scenario/scenario.h"

namespace surfvp {
namespace {
using test::fresh_dir;
using test::write_file;

std::string scenario(const std::string& text) { return write_file(fresh_dir("scenario"), "s.yaml", text); }

TEST(Scenario, ValuesCarryUnitsAndOrigins) {
    const std::string path = scenario(
        "name: demo\n"
        "description: a test\n"
        "plb2:\n"
        "  width: 64 bit\n"
        "  clock: 125 MHz\n");
    const Config c = load_scenario(path, {"plb2.clock=150 MHz"});
    EXPECT_EQ(c.name, "demo");
    EXPECT_EQ(c.description, "a test");
    EXPECT_EQ(c.bits("plb2.width"), 64u);
    EXPECT_DOUBLE_EQ(c.frequency("plb2.clock").hz, 150e6);
    EXPECT_DOUBLE_EQ(c.frequency("plb1.clock").hz, 100e6);  // default
    for (const auto& e : c.entries()) {
        if (e.spec->key == "plb2.width") {
            EXPECT_EQ(e.origin, path + ":4");
        } else if (e.spec->key == "plb2.clock") {
            EXPECT_EQ(e.origin, "--set");
        } else if (e.spec->key == "plb1.clock") {
            EXPECT_EQ(e.origin, "default");
        }
    }
}

TEST(Scenario, NameDefaultsToTheFileStem) {
    EXPECT_EQ(load_scenario(scenario("cpu:\n  clock: 300 MHz\n"), {}).name, "s");
}

void expect_bad(const std::string& text, const std::vector<std::string>& sets, const std::vector<std::string>& words) {
    const std::string path = scenario(text);
    try {
        load_scenario(path, sets);
        FAIL() << "accepted:\n" << text;
    } catch (const ConfigError& e) {
        for (const auto& w : words) {
            const std::string expected = w.rfind("FILE", 0) == 0 ? path + w.substr(4) : w;
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << "message: " << e.what();
        }
    }
}

TEST(ScenarioErrors, UnknownKeyNamesFileLineKeyAndTheClosestKey) {
    expect_bad("name: x\nplb2:\n  widht: 64 bit\n", {},
               {"FILE:3", "'plb2.widht' is not a parameter", "did you mean 'plb2.width'"});
}

TEST(ScenarioErrors, UnknownSection) {
    expect_bad("plb9:\n  clock: 1 MHz\n", {}, {"FILE:2", "'plb9.clock' is not a parameter"});
}

TEST(ScenarioErrors, WrongUnit) {
    expect_bad("plb1:\n  clock: 100 bit\n", {}, {"FILE:2", "plb1.clock", "wrong unit 'bit'", "expected frequency"});
}

TEST(ScenarioErrors, MissingUnit) {
    expect_bad("memory:\n  latency: 25\n", {}, {"FILE:2", "memory.latency", "has no unit"});
}

TEST(ScenarioErrors, OutOfRange) {
    expect_bad("plb1:\n  max_burst: 32 beats\n", {}, {"FILE:2", "out of range", "between 2 beats and 16 beats"});
}

TEST(ScenarioErrors, NotAChoice) {
    expect_bad("plb1:\n  arbitration: lottery\n", {}, {"FILE:2", "not one of: round_robin, fixed_priority"});
}

TEST(ScenarioErrors, MissingFile) {
    try {
        load_scenario("/nonexistent/x.yaml", {});
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_STREQ(e.what(), "/nonexistent/x.yaml: no such scenario file");
    }
}

TEST(ScenarioErrors, NotYaml) { expect_bad("plb1:\n  clock: [100 MHz\n", {}, {"FILE:", "not valid YAML"}); }

TEST(ScenarioErrors, SectionMustBeAMap) { expect_bad("plb1: 100 MHz\n", {}, {"FILE:1", "'plb1' must be a section"}); }

TEST(ScenarioErrors, ValueMustBeSingle) {
    expect_bad("plb1:\n  clock: [1, 2]\n", {}, {"FILE:2", "expected a single value, found a list"});
}

TEST(ScenarioErrors, DuplicateKey) {
    expect_bad("plb1:\n  clock: 1 MHz\n  clock: 2 MHz\n", {}, {"FILE:3", "set twice"});
}

TEST(ScenarioErrors, RootMustBeAMap) { expect_bad("- a\n- b\n", {}, {"FILE:1", "map of sections"}); }

TEST(ScenarioErrors, SetWithoutEquals) { expect_bad("", {"plb2.width"}, {"--set 'plb2.width': expected KEY=VALUE"}); }

TEST(ScenarioErrors, SetOfUnknownKey) { expect_bad("", {"cpu.clok=1 MHz"}, {"--set", "did you mean 'cpu.clock'"}); }

// Found by tests/fuzz (scenario): a description with a stray byte loaded, but config.yaml
// wrote U+FFFD for it, so the effective configuration did not load back to the same text.
TEST(ScenarioErrors, TextThatIsNotUtf8) {
    expect_bad("name: x\ndescription: caf\xe9\n", {}, {"FILE:2", "description: not UTF-8 text"});
    expect_bad("surf:\n  source: \xc0\xaf.png\n", {}, {"FILE:2", "surf.source: not UTF-8 text"});  // overlong '/'
    expect_bad("", {"surf.source=\xed\xa0\x80.png"}, {"--set", "not UTF-8 text"});                 // a surrogate
    EXPECT_EQ(load_scenario(scenario("description: caf\xc3\xa9 \xf0\x9f\x9a\x80\n"), {}).description,
              "caf\xc3\xa9 \xf0\x9f\x9a\x80");
}

TEST(Scenario, EffectiveConfigurationLoadsBackToTheSameValues) {
    const Config original = load_scenario(scenario("plb2:\n  width: 64 bit\n"), {"cpu.clock=300 MHz"});
    const std::string copy = write_file(fresh_dir("copy"), "effective.yaml", original.to_yaml());
    const Config again = load_scenario(copy, {});
    ASSERT_EQ(original.entries().size(), again.entries().size());
    for (size_t i = 0; i < original.entries().size(); ++i)
        EXPECT_EQ(original.entries()[i].value, again.entries()[i].value) << original.entries()[i].spec->key;
    EXPECT_NE(original.to_yaml().find("width: 64 bit  # "), std::string::npos) << original.to_yaml();
    EXPECT_NE(original.to_yaml().find("# --set"), std::string::npos);
}

// Found by tests/fuzz scenario: a description with lone carriage returns did not load back from
// config.yaml as it was; name and description are written double-quoted.
TEST(Scenario, NameAndDescriptionLoadBackAsTheyWere) {
    const std::string path = write_file(
        fresh_dir("cr"), "cr.yaml",
        test::slurp(SURFVP_SOURCE_DIR "/tests/fuzz/regressions/scenario/description_with_lone_carriage_returns"));
    const Config original = load_scenario(path, {});
    ASSERT_NE(original.description.find('\r'), std::string::npos);
    const Config again = load_scenario(write_file(fresh_dir("cr_again"), "config.yaml", original.to_yaml()), {});
    EXPECT_EQ(again.name, original.name);
    EXPECT_EQ(again.description, original.description);
}

TEST(Scenario, EveryParameterDefaultIsValidAndHasASource) {
    for (const ParamSpec& p : parameter_table()) {
        EXPECT_NO_THROW(parse_value(p, p.default_value)) << p.key;
        EXPECT_FALSE(p.description.empty()) << p.key;
        EXPECT_EQ(p.source[0], '[') << p.key << ": the source starts with its tag";
        EXPECT_EQ(std::count(p.key.begin(), p.key.end(), '.'), 1) << p.key << ": keys are section.name";
    }
}

TEST(Scenario, ShippedScenariosAllLoad) {
    const auto shipped = shipped_scenarios();
    ASSERT_FALSE(shipped.empty());
    for (const auto& s : shipped) EXPECT_NO_THROW(load_scenario(s.path, {})) << s.path;
}

}  // namespace
}  // namespace surfvp
