// Sweeps (docs/sweeps.md): the file's axes become points, each point runs as a re-simulation
// and is recorded in SQLite as it ends; a sweep run again resumes, shards merge into the
// results of one whole run, a point that cannot run is recorded and the others go on.
#include <filesystem>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <gtest/gtest.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <sqlite3.h>

#include "cli.h"
#include "platform/report/chart_ticks.h"
#include "platform/scenario/config.h"
#include "platform/sweep/sweep_plan.h"
#include "platform/sweep/sweep_results.h"
#include "platform/sweep/sweep_store.h"

namespace surfvp::test {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::json;

// The budget scenario, small and short: 3 frames of 256x192.
std::string small_sweep(const std::string& dir, const std::string& axes, const std::string& extra = "") {
    return write_file(dir, "sweep.yaml",
                      "name: small\n"
                      "scenario: " +
                          kBudget +
                          "\n"
                          "set:\n"
                          "  surf.frames: 3\n  surf.width: 256\n  surf.height: 192\n  surf.target_keypoints: 20\n" +
                          extra + "axes:\n" + axes);
}

const std::string kTwoByTwo = "  fhg.clock: {from: 25 MHz, to: 50 MHz, step: 25 MHz}\n  fhg.read_buses: [2, 4]\n";

TEST(SweepPlan, RangesWithUnitsAndCartesianOrZippedPoints) {
    EXPECT_EQ(expand_range("75 MHz", "150 MHz", "25 MHz", "here"),
              (std::vector<std::string>{"75 MHz", "100 MHz", "125 MHz", "150 MHz"}));
    EXPECT_EQ(expand_range("0.1", "0.3", "0.1", "here"), (std::vector<std::string>{"0.1", "0.2", "0.3"}));
    EXPECT_EQ(expand_range("1 ms", "2.5 ms", "1 ms", "here"), (std::vector<std::string>{"1 ms", "2 ms"}));
    const std::string dir = fresh_dir("plan");
    const SweepPlan plan = load_sweep(small_sweep(dir, kTwoByTwo + "  fhg.fifo_lines: [56, 60, 64]\n"));
    ASSERT_EQ(plan.points.size(), 12u);
    EXPECT_EQ(plan.points[0].id, "fhg.clock=25 MHz, fhg.read_buses=2, fhg.fifo_lines=56");
    EXPECT_EQ(plan.points[11].id, "fhg.clock=50 MHz, fhg.read_buses=4, fhg.fifo_lines=64");
    EXPECT_EQ(plan.config(plan.points[5]).value("fhg.read_buses"), "4");
    EXPECT_EQ(plan.config(plan.points[5]).value("surf.frames"), "3");
    const SweepPlan zipped = load_sweep(small_sweep(dir, kTwoByTwo, "combine: zip\n"));
    ASSERT_EQ(zipped.points.size(), 2u);
    EXPECT_EQ(zipped.points[1].id, "fhg.clock=50 MHz, fhg.read_buses=4");
}

TEST(SweepPlan, BadAxesAreNamedAtTheirLine) {
    const std::string dir = fresh_dir("bad_plan");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"  fhg.speed: [1, 2]\n", "sweep.yaml:9: axis fhg.speed: no such parameter"},
        {"  fhg.read_buses: [2, 0]\n", "sweep.yaml:9: fhg.read_buses"},
        {"  fhg.clock: {from: 50 MHz, to: 25 MHz, step: 5 MHz}\n", "to (25 MHz) is below from (50 MHz)"},
        {"  fhg.clock: {from: 50 MHz, to: 60 MHz, step: 0 MHz}\n", "step 0 MHz must be above zero"},
        {"  fhg.clock: {from: 50 MHz, to: 60 GHz, step: 5 MHz}\n", "must share one unit"},
        {"  fhg.clock: {from: 50 MHz, to: 60 MHz}\n", "'step' is missing"},
        {"  fhg.clock: {from: 1e400 MHz, to: 60 MHz, step: 5 MHz}\n",
         "'1e400 MHz' is out of range (not a finite number)"},  // was exit 3
        {"  fhg.clock: {from: 50 MHz, to: 60 MHz, step: fast}\n", "'fast' is not a number with an optional unit"},
        {"  surf.frames: [2, 4]\n", "axis surf.frames is also in set:"},
    };
    for (const auto& [axes, message] : cases) {
        try {
            load_sweep(small_sweep(dir, axes));
            ADD_FAILURE() << "accepted: " << axes;
        } catch (const ConfigError& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    }
    try {
        load_sweep(small_sweep(dir, "  fhg.clock: [25 MHz, 50 MHz]\n  fhg.read_buses: [2, 4, 6]\n", "combine: zip\n"));
        ADD_FAILURE() << "zip of unequal axes accepted";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("zip needs axes of one length"), std::string::npos) << e.what();
    }
}

// The number of points is known, and checked, before any point is made: five axes of a
// thousand values each are refused at once, naming every axis and its size; four of 100000
// (a product past 2^64) are not wrapped around to a small number.
TEST(SweepPlan, TooManyPointsAreRefusedBeforeTheyAreMade) {
    const std::string dir = fresh_dir("too_many");
    const std::string thousand =
        "  fhg.clock: {from: 1 MHz, to: 1000 MHz, step: 1 MHz}\n"
        "  smoke.copies: {from: 1, to: 1000, step: 1}\n"
        "  smoke.polls: {from: 0, to: 999, step: 1}\n"
        "  smoke.poll_interval: {from: 0 cycles, to: 999 cycles, step: 1 cycles}\n"
        "  plb1.clock: {from: 1 MHz, to: 1000 MHz, step: 1 MHz}\n";
    const auto refusal = [&dir](const std::string& name, const std::string& text) {
        try {
            load_sweep(write_file(dir, name, text));
        } catch (const ConfigError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(refusal("s.yaml", "scenario: smoke\naxes:\n" + thousand),
              dir +
                  "/s.yaml:2: combine: the axes make 1000000000000000 points, more than the 100000 a sweep may have: "
                  "fhg.clock (1000 values) x smoke.copies (1000 values) x smoke.polls (1000 values) x "
                  "smoke.poll_interval (1000 values) x plb1.clock (1000 values)");
    const std::string huge =
        "combine: cartesian\naxes:\n"
        "  smoke.copies: {from: 1, to: 100000, step: 1}\n"
        "  smoke.polls: {from: 1, to: 100000, step: 1}\n"
        "  smoke.poll_interval: {from: 1 cycles, to: 100000 cycles, step: 1 cycles}\n"
        "  fhg.clock: {from: 1 kHz, to: 100000 kHz, step: 1 kHz}\n";
    const std::string message = refusal("huge.yaml", "scenario: smoke\n" + huge);
    EXPECT_NE(message.find("huge.yaml:2: combine: the axes make 1e+20 points, more than the 100000"), std::string::npos)
        << message;
    // At the limit, the points are made.
    const SweepPlan at_limit = load_sweep(write_file(dir, "ok.yaml",
                                                     "scenario: smoke\naxes:\n"
                                                     "  smoke.copies: {from: 1, to: 1000, step: 1}\n"
                                                     "  smoke.polls: {from: 1, to: 100, step: 1}\n"));
    EXPECT_EQ(at_limit.points.size(), 100000u);
    EXPECT_EQ(at_limit.points.back().id, "smoke.copies=1000, smoke.polls=100");
}

// The name is the default sweep folder's (traces/<name>): a scenario's rule, at its line.
TEST(SweepPlan, ANameFollowsTheScenarioNameRuleAtItsLine) {
    const std::string dir = fresh_dir("names");
    auto named = [&](const std::string& name) {
        return write_file(dir, "named.yaml",
                          "name: " + name + "\nscenario: smoke\naxes:\n  plb2.width: [32 bit, 64 bit]\n");
    };
    for (const std::string name : {"../up", "a/b", "'..'", "'.'", "'a\\b'", "\"tab\\there\"", "''"}) {
        try {
            load_sweep(named(name));
            ADD_FAILURE() << "accepted: " << name;
        } catch (const ConfigError& e) {
            EXPECT_NE(std::string(e.what()).find("named.yaml:1: name '"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("cannot name the output folder"), std::string::npos) << e.what();
        }
    }
    // Text that results.json cannot hold is refused at its line, not when the results are written.
    try {
        load_sweep(named("\xff\xfe"));
        ADD_FAILURE() << "a name that is not UTF-8 accepted";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("named.yaml:1: name: not UTF-8 text"), std::string::npos) << e.what();
    }
    // Without a name, the file's stem is the name, under the same rule.
    try {
        load_sweep(write_file(dir, "..yaml", "scenario: smoke\n"));
        ADD_FAILURE() << "the stem '.' accepted";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("..yaml: name '.' cannot name"), std::string::npos) << e.what();
    }
    // What a scenario's name may hold, a sweep's may too (a space, '<', a quote).
    EXPECT_EQ(load_sweep(named("'a <b> & \"c\"'")).name, "a <b> & \"c\"");
}

TEST(SweepResults, TheParetoFrontIsThePointsNoOtherBeats) {
    auto row = [](size_t i, double fps, double bram) {
        return SweepRow{i, std::to_string(i), Json::object(), 0, "", {{"fps", fps}, {"bram36", bram}}, 0};
    };
    std::vector<SweepRow> rows = {row(0, 10, 60), row(1, 12, 60), row(2, 8, 40), row(3, 8, 50), row(4, 12, 60)};
    rows.push_back(SweepRow{5, "5", Json::object(), 3, "crashed", Json::object(), 0});
    rows.push_back(row(6, 12.001, 62));  // 0.01 % faster for two more block RAMs: a tie on frames/s, so beaten
    const auto objectives = pareto_objectives(rows);
    ASSERT_EQ(objectives.size(), 2u);
    EXPECT_EQ(pareto_front(rows, objectives), (std::vector<bool>{false, true, true, false, true, false, false}));
    // A point that does not fit the device, or broke, trades off nothing: the fastest and
    // cheapest is left off the front, and beats no other.
    rows.push_back(SweepRow{7, "7", Json::object(), 0, "", {{"fps", 20}, {"bram36", 30}, {"fits", false}}, 0});
    rows.push_back(SweepRow{8, "8", Json::object(), 6, "", {{"fps", 20}, {"bram36", 30}, {"fits", true}}, 0});
    EXPECT_EQ(pareto_front(rows, pareto_objectives(rows)),
              (std::vector<bool>{false, true, true, false, true, false, false, false, false}));
}

// Plot ticks are round numbers: 1, 2 or 5 times a power of ten, covering the data.
TEST(SweepResults, PlotTicksAreRoundNumbers) {
    const Ticks t = round_ticks(0, 9.43);
    EXPECT_EQ(t.at, (std::vector<double>{0, 2, 4, 6, 8, 10}));
    EXPECT_EQ(tick_label(t.at[1], t.step), "2");
    const Ticks w = round_ticks(2.376, 2.597, 4);
    EXPECT_DOUBLE_EQ(w.step, 0.1);
    EXPECT_NEAR(w.lo(), 2.3, 1e-12);
    EXPECT_NEAR(w.hi(), 2.6, 1e-12);
    EXPECT_EQ(tick_label(w.at[1], w.step), "2.4");
    EXPECT_EQ(round_ticks(83, 84).step, 0.2);
}

Json results(const std::string& dir) { return Json::parse(slurp(dir + "/results.json")); }

TEST(Sweep, PointsRunInParallelAndResultsComeOutAsCsvJsonAndPlots) {
    const std::string dir = fresh_dir("sweep");
    const auto r = surfvp("sweep " + small_sweep(dir, kTwoByTwo) + " --jobs 2 --out " + dir + "/out");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json j = results(dir + "/out");
    ASSERT_EQ(j["points"].size(), 4u);
    for (const auto& p : j["points"]) {
        EXPECT_EQ(p["status"], "passed") << p;
        EXPECT_GT(p["figures"]["fps"].get<double>(), 0.0) << p;
        EXPECT_GT(p["figures"]["keypoints_per_frame"].get<double>(), 0.0) << p;
        EXPECT_FALSE(p["figures"]["bottleneck"].get<std::string>().empty()) << p;
        // FPGA resources ride along (docs/resources.md): the sequence memory's words (179 bits
        // with two read buses, 231 with four: docs/sequence-memory.md) take three and four
        // 72-bit columns of block RAM.
        EXPECT_EQ(p["figures"]["bram36"], p["params"]["fhg.read_buses"] == "2" ? 84 : 85) << p;
        EXPECT_TRUE(p["figures"]["fits"].get<bool>()) << p;
    }
    // At 25 MHz the FHG is the bottleneck: twice its clock, more frames/s.
    EXPECT_EQ(j["points"][0]["figures"]["bottleneck"], "fhg");
    EXPECT_GT(j["points"][2]["figures"]["fps"].get<double>(), 1.5 * j["points"][0]["figures"]["fps"].get<double>());
    const std::string csv = slurp(dir + "/out/results.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
    EXPECT_EQ(csv.rfind("point,fhg.clock,fhg.read_buses,status,exit,fps,", 0), 0u) << csv.substr(0, 200);
    for (const char* plot : {"plot_fhg.clock.svg", "plot_fhg.read_buses.svg"})
        EXPECT_NE(slurp(dir + "/out/" + plot).find("<circle"), std::string::npos) << plot;
    // The same points again: nothing is rerun.
    const auto again = surfvp("sweep " + dir + "/sweep.yaml --out " + dir + "/out");
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_NE(again.err.find("4 of 4 points already done"), std::string::npos) << again.err;
    EXPECT_EQ(results(dir + "/out")["points"], j["points"]);
}

// A base scenario that evaluates its keypoints gives each row its quality, and the front weighs it.
TEST(Sweep, QualityComesWithAScenarioThatEvaluates) {
    const std::string dir = fresh_dir("quality");
    const std::string file =
        write_file(dir, "q.yaml",
                   "scenario: " + std::string(SURFVP_SOURCE_DIR) +
                       "/scenarios/graf.yaml\n"
                       "set: {surf.target_keypoints: 300}\naxes:\n  surf.haar: [rounded, exact]\n");
    const auto r = surfvp("sweep " + file + " --quiet --out " + dir + "/out");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json j = results(dir + "/out");
    bool weighed = false;
    for (const auto& o : j["pareto_objectives"]) weighed = weighed || o["figure"] == "precision";
    EXPECT_TRUE(weighed) << j["pareto_objectives"];
    for (const auto& p : j["points"]) {
        EXPECT_GT(p["figures"]["repeatability"].get<double>(), 0.3) << p;
        EXPECT_LT(p["figures"]["repeatability"].get<double>(), 1.0) << p;
        EXPECT_GT(p["figures"]["precision"].get<double>(), 0.3) << p;
    }
    // The Haar mode is the descriptor's: the detector's repeatability is the same, the precision not.
    EXPECT_EQ(j["points"][0]["figures"]["repeatability"], j["points"][1]["figures"]["repeatability"]);
    EXPECT_NE(j["points"][0]["figures"]["precision"], j["points"][1]["figures"]["precision"]);
}

TEST(Sweep, ShardsMergeIntoTheResultsOfOneRun) {
    const std::string dir = fresh_dir("shards");
    const std::string file = small_sweep(dir, kTwoByTwo);
    ASSERT_EQ(surfvp("sweep " + file + " --quiet --out " + dir + "/whole").exit_code, 0);
    for (const char* shard : {"1/3", "2/3", "3/3"})
        ASSERT_EQ(surfvp("sweep " + file + " --quiet --shard " + shard + " --out " + dir + "/sharded").exit_code, 0)
            << shard;
    EXPECT_FALSE(fs::exists(dir + "/sharded/results.json"));
    const auto merged = surfvp("sweep-merge " + dir + "/sharded");
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    EXPECT_NE(merged.err.find("3 shard databases, 4 new points"), std::string::npos) << merged.err;
    Json whole = results(dir + "/whole"), sharded = results(dir + "/sharded");
    for (Json* j : {&whole, &sharded})
        for (auto& p : (*j)["points"]) p.erase("wall_s");
    EXPECT_EQ(whole, sharded);
}

// A point that misses its budget or breaks ran: its row says which (missed, broken) with the
// exit code `surfvp run` gives it, and the sweep ends well.
TEST(Sweep, APointThatMissesItsBudgetOrBreaksSaysWhichInItsRow) {
    const std::string dir = fresh_dir("missed_broken");
    const auto r = surfvp("sweep " + small_sweep(dir, "  fhg.maxima_fifo_depth: [4, 1024]\n  budget.fps: [10, 400]\n") +
                          " --quiet --out " + dir + "/out");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const Json j = results(dir + "/out");
    ASSERT_EQ(j["points"].size(), 4u);
    const std::vector<std::pair<std::string, int>> expected{{"broken", 6}, {"broken", 6}, {"passed", 0}, {"missed", 1}};
    for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(j["points"][i]["status"], expected[i].first) << j["points"][i];
        EXPECT_EQ(j["points"][i]["exit"], expected[i].second) << j["points"][i];
    }
    EXPECT_NE(slurp(dir + "/out/results.csv").find(",missed,1,"), std::string::npos);
    // On a terminal (script(1) gives it one) the summary is a line of its own after the bar.
    const std::string tty = dir + "/tty.txt";
    ASSERT_EQ(std::system(("script -qec '" + std::string(SURFVP_BINARY) + " sweep " + dir +
                           "/sweep.yaml --fresh --out " + dir + "/out' " + tty + " > /dev/null")
                              .c_str()),
              0);
    const std::string shown = slurp(tty);
    EXPECT_NE(shown.find("\r\nsurfvp: small: 4 points run (0 not run), 1 of 4 meet the budget; "), std::string::npos)
        << shown;
    EXPECT_NE(shown.find("\rsurfvp: small: ["), std::string::npos) << shown;
}

TEST(Sweep, APointThatCannotRunIsRecordedAndTheOthersGoOn) {
    const std::string dir = fresh_dir("failing");
    // 8 MiB holds two buffer sets of 256x192 frames, 1 MiB does not.
    const auto r =
        surfvp("sweep " + small_sweep(dir, "  memory.size: [1 MiB, 8 MiB]\n") + " --quiet --out " + dir + "/out");
    EXPECT_EQ(r.exit_code, 1) << r.err;
    const Json j = results(dir + "/out");
    ASSERT_EQ(j["points"].size(), 2u);
    EXPECT_EQ(j["points"][0]["status"], "error");
    EXPECT_EQ(j["points"][0]["exit"], 2);
    EXPECT_NE(j["points"][0]["error"].get<std::string>().find("memory.size"), std::string::npos) << j["points"][0];
    EXPECT_EQ(j["points"][1]["status"], "passed") << j["points"][1];
    // Another sweep in the same folder would mix two sweeps' points: refused.
    const std::string other = write_file(dir, "other.yaml", "scenario: smoke\naxes:\n  plb2.width: [32 bit, 64 bit]\n");
    const auto mixed = surfvp("sweep " + other + " --out " + dir + "/out");
    EXPECT_EQ(mixed.exit_code, 2);
    EXPECT_NE(mixed.err.find("holds the points of another sweep"), std::string::npos) << mixed.err;
}

// The smoke scenario, copied next to the sweep file and named by a relative path: a sweep of
// two points that runs in a fraction of a second.
std::string smoke_sweep(const std::string& dir, const std::string& body) {
    fs::copy_file(std::string(SURFVP_SOURCE_DIR) + "/scenarios/smoke.yaml", dir + "/base.yaml",
                  fs::copy_options::overwrite_existing);
    return write_file(dir, "s.yaml", "name: tiny\nscenario: base.yaml\n" + body);
}
const std::string kTinyAxes = "set: {smoke.copies: 2, surf.source: frame.png}\naxes:\n  plb2.width: [32 bit, 64 bit]\n";

// In `dir` for as long as it lives.
class InFolder {
public:
    explicit InFolder(const std::string& dir) : before_(fs::current_path()) { fs::current_path(dir); }
    ~InFolder() { fs::current_path(before_); }

private:
    fs::path before_;
};

// A sweep is its content: run from another folder, or through another spelling of its file
// (relative, with '..', absolute, a symbolic link), it resumes; shards so spelt merge.
TEST(Sweep, ItsIdentityIsItsContentNotTheSpellingOfItsFiles) {
    const std::string dir = fresh_dir("identity");
    fs::create_directories(dir + "/a");
    smoke_sweep(dir + "/a", kTinyAxes);
    fs::create_directory_symlink(dir + "/a", dir + "/link");
    fs::create_symlink(dir + "/a/s.yaml", dir + "/s_link.yaml");  // the file itself, linked from another folder
    {
        InFolder here(dir + "/a");
        const auto r = surfvp("sweep s.yaml --quiet --out out");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        ASSERT_EQ(surfvp("sweep s.yaml --quiet --shard 1/2 --out sharded").exit_code, 0);
    }
    const Json first = results(dir + "/a/out");
    ASSERT_EQ(first["points"].size(), 2u);
    // A path among the sets is kept as its file's one absolute spelling.
    const std::string frame = (fs::canonical(dir + "/a") / "frame.png").string();
    EXPECT_EQ(slurp(dir + "/a/out/results.json").find("frame.png"),
              std::string::npos);  // sets are not in the results...
    InFolder here(dir);
    for (const std::string& spelling : std::vector<std::string>{"a/s.yaml", "./a/../a/s.yaml", dir + "/a/s.yaml",
                                                                dir + "/link/s.yaml", "link/./s.yaml", "s_link.yaml"}) {
        const auto again = surfvp("sweep " + spelling + " --out a/out");
        EXPECT_EQ(again.exit_code, 0) << spelling << ": " << again.err;
        EXPECT_NE(again.err.find("2 of 2 points already done"), std::string::npos) << spelling << ": " << again.err;
    }
    EXPECT_EQ(results(dir + "/a/out")["points"].size(), 2u);
    // Shard 2 through the link, from another folder: the merge takes both shards as one sweep's.
    ASSERT_EQ(surfvp("sweep " + dir + "/link/s.yaml --quiet --shard 2/2 --out " + dir + "/a/sharded").exit_code, 0);
    const auto merged = surfvp("sweep-merge a/sharded");
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    Json whole = first["points"], sharded = results(dir + "/a/sharded")["points"];
    for (Json* j : {&whole, &sharded})
        for (auto& p : *j) p.erase("wall_s");
    EXPECT_EQ(whole, sharded);
    // ...but an axis of paths names each point by its file's one spelling.
    const SweepPlan plan = load_sweep(dir + "/link/s.yaml");
    const SweepPlan paths = load_sweep(
        write_file(dir + "/link", "p.yaml", "scenario: base.yaml\naxes:\n  surf.source: [x.png, ../a/y.png]\n"));
    EXPECT_EQ(paths.points[0].id, "surf.source=" + (fs::canonical(dir + "/a") / "x.png").string());
    EXPECT_EQ(paths.points[1].id, "surf.source=" + (fs::canonical(dir + "/a") / "y.png").string());
    EXPECT_NE(plan.fingerprint.find(frame), std::string::npos) << plan.fingerprint;
    EXPECT_EQ(plan.fingerprint, load_sweep("a/../link/s.yaml").fingerprint);
}

// A sweep edited and run again into its folder is refused with what changed; the folder is
// left as it was. --fresh discards the old sweep's files (only those) and runs the new one.
TEST(Sweep, AnEditedSweepIsRefusedWithWhatChangedUnlessFresh) {
    const std::string dir = fresh_dir("edited");
    const std::string file = smoke_sweep(dir, kTinyAxes);
    ASSERT_EQ(surfvp("sweep " + file + " --quiet --out " + dir + "/out").exit_code, 0);
    write_file(dir + "/out", "notes.txt", "mine");
    const std::string db = slurp(dir + "/out/sweep.db"), json = slurp(dir + "/out/results.json");
    auto refused = [&](const std::string& body, const std::vector<std::string>& phrases) {
        smoke_sweep(dir, body);
        const auto r = surfvp("sweep " + file + " --out " + dir + "/out");
        EXPECT_EQ(r.exit_code, 2) << body << r.err;
        EXPECT_NE(r.err.find(dir + "/out/sweep.db: holds the points of another sweep: "), std::string::npos) << r.err;
        for (const std::string& phrase : phrases)
            EXPECT_NE(r.err.find(phrase), std::string::npos) << phrase << "\n" << r.err;
        EXPECT_NE(r.err.find("give --fresh to discard them"), std::string::npos) << r.err;
        EXPECT_EQ(slurp(dir + "/out/sweep.db"), db);
        EXPECT_EQ(slurp(dir + "/out/results.json"), json);
    };
    refused("set: {smoke.copies: 2, surf.source: frame.png}\naxes:\n  plb2.width: [64 bit]\n",
            {"axis plb2.width: values changed (32 bit, 64 bit; now 64 bit)"});
    refused("set: {smoke.copies: 3, smoke.polls: 1}\naxes:\n  plb2.width: [32 bit, 64 bit]\n",
            {"set changed (smoke.copies: 2, now 3; smoke.polls added; surf.source removed)"});
    refused("set: {smoke.copies: 2, surf.source: frame.png}\naxes:\n  plb1.width: [32 bit, 64 bit]\n",
            {"axes added: plb1.width", "axes removed: plb2.width"});
    refused(kTinyAxes + "  plb1.width: [32 bit, 64 bit]\ncombine: zip\n",
            {"axes added: plb1.width", "combine changed (cartesian, now zip)"});
    // The same sets in another order are the same sweep; the base scenario's text is not.
    smoke_sweep(dir, "set: {surf.source: frame.png, smoke.copies: 2}\naxes:\n  plb2.width: [32 bit, 64 bit]\n");
    EXPECT_EQ(surfvp("sweep " + file + " --quiet --out " + dir + "/out").exit_code, 0);
    std::string text = slurp(dir + "/base.yaml");
    text.replace(text.find("buffer: 64 KiB"), 14, "buffer: 32 KiB");
    write_file(dir, "base.yaml", text);
    const auto base = surfvp("sweep " + dir + "/s.yaml --out " + dir + "/out");
    EXPECT_EQ(base.exit_code, 2);
    EXPECT_NE(base.err.find("another sweep: base scenario changed;"), std::string::npos) << base.err;

    // --fresh: the new sweep's points and plots only; a file of the user's stays.
    smoke_sweep(dir, "axes:\n  plb1.width: [32 bit, 64 bit, 128 bit]\n");
    write_file(dir + "/out", "shard-1-of-2.db", "");  // an old shard of no sweep: not a database of another sweep
    const auto fresh = surfvp("sweep " + file + " --quiet --fresh --out " + dir + "/out");
    ASSERT_EQ(fresh.exit_code, 0) << fresh.err;
    const Json j = results(dir + "/out");
    ASSERT_EQ(j["points"].size(), 3u);
    EXPECT_EQ(j["points"][2]["params"]["plb1.width"], "128 bit");
    EXPECT_TRUE(fs::exists(dir + "/out/plot_plb1.width.svg"));
    EXPECT_FALSE(fs::exists(dir + "/out/plot_plb2.width.svg"));
    EXPECT_FALSE(fs::exists(dir + "/out/shard-1-of-2.db"));  // a whole sweep starts over with every database
    EXPECT_EQ(slurp(dir + "/out/notes.txt"), "mine");
    // --fresh on the same sweep runs every point again.
    const auto again = surfvp("sweep " + file + " --fresh --out " + dir + "/out");
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(again.err.find("already done"), std::string::npos) << again.err;
    EXPECT_NE(again.err.find("3 points run"), std::string::npos) << again.err;
}

// A point that could not run (here: its frame is missing) is run again when the sweep is
// resumed, unless --keep-failed; one that ran and failed a check (here: an unreachable
// budget) is a result and is not. While any point could not run, the sweep exits 1.
TEST(Sweep, PointsThatCouldNotRunAreRunAgainOnResume) {
    const std::string dir = fresh_dir("retry");
    fs::copy_file(kOpencvData + "/graf1.png", dir + "/a.png");
    const std::string file =
        write_file(dir, "s.yaml",
                   "scenario: " + kBudget +
                       "\n"
                       "set: {surf.frames: 3, surf.width: 256, surf.height: 192, surf.target_keypoints: 20, "
                       "budget.fps: 100000}\n"
                       "axes:\n  surf.source: [a.png, b.png]\n");
    const std::string out = " --out " + dir + "/out";
    const auto first = surfvp("sweep " + file + " --quiet" + out);
    EXPECT_EQ(first.exit_code, 1) << first.err;
    EXPECT_NE(first.err.find("1 points could not run: point 1 (surf.source=" + dir + "/b.png, exit 2)"),
              std::string::npos)
        << first.err;
    Json j = results(dir + "/out");
    EXPECT_EQ(j["points"][0]["status"], "missed");
    EXPECT_EQ(j["points"][0]["exit"], 1);
    EXPECT_EQ(j["points"][1]["status"], "error");
    const auto wall0 = j["points"][0]["wall_s"];

    const auto kept = surfvp("sweep " + file + " --keep-failed" + out);
    EXPECT_EQ(kept.exit_code, 1) << kept.err;  // not 0: the point is still not run
    EXPECT_NE(kept.err.find("2 of 2 points already done"), std::string::npos) << kept.err;
    EXPECT_NE(kept.err.find("1 that could not run kept as recorded"), std::string::npos) << kept.err;
    EXPECT_NE(kept.err.find("0 points run"), std::string::npos) << kept.err;

    const auto still = surfvp("sweep " + file + out);  // run again, and still missing
    EXPECT_EQ(still.exit_code, 1) << still.err;
    EXPECT_NE(
        still.err.find("1 of 2 points already done in " + dir + "/out/sweep.db; 1 that could not run are run again"),
        std::string::npos)
        << still.err;

    fs::copy_file(kOpencvData + "/graf1.png", dir + "/b.png");
    const auto again = surfvp("sweep " + file + out);
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_NE(again.err.find("1 points run (0 not run)"), std::string::npos) << again.err;
    j = results(dir + "/out");
    EXPECT_EQ(j["points"][0]["wall_s"], wall0);  // the failed check was not run again
    EXPECT_EQ(j["points"][1]["status"], "missed");
    EXPECT_EQ(j["points"][1]["figures"]["fps"], j["points"][0]["figures"]["fps"]);
}

// Every text of an element in an SVG (its <text> and <title> elements), or nothing when the
// file is not well-formed XML.
std::optional<std::vector<std::string>> svg_texts(const std::string& svg) {
    std::unique_ptr<xmlDoc, decltype(&xmlFreeDoc)> doc(
        xmlReadMemory(svg.data(), int(svg.size()), "plot.svg", nullptr,
                      XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING),
        xmlFreeDoc);
    if (!doc) return std::nullopt;
    std::vector<std::string> texts;
    std::function<void(xmlNodePtr)> walk = [&](xmlNodePtr n) {
        for (; n; n = n->next) {
            if (n->type == XML_ELEMENT_NODE &&
                (xmlStrEqual(n->name, BAD_CAST "text") || xmlStrEqual(n->name, BAD_CAST "title"))) {
                xmlChar* t = xmlNodeGetContent(n);
                texts.emplace_back(reinterpret_cast<const char*>(t));
                xmlFree(t);
            }
            walk(n->children);
        }
    };
    walk(xmlDocGetRootElement(doc.get()));
    return texts;
}

// Names, values and ids holding markup, '&', quotes and a control character give plots that
// are well-formed SVG and show those texts as text.
TEST(Sweep, PlotsEscapeEveryTextTheyShow) {
    const std::string dir = fresh_dir("escape");
    const std::string file = smoke_sweep(dir, "");
    write_file(dir, "s.yaml",
               "name: \"<script>alert('x') & \\\"q\\\"\"\n"
               "description: \"<script>evil()</script> & 'single' \\\"double\\\"\"\n"
               "scenario: base.yaml\n"
               "axes:\n  surf.source: [\"<script>a & 'b'.png\", \"c\\\"d<e>\\x01.png\"]\n");
    const auto r = surfvp("sweep " + file + " --quiet --out " + dir + "/out");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string name = "<script>alert('x') & \"q\"";
    for (const char* plot : {"plot_surf.source.svg", "pareto.svg"}) {
        const std::string svg = slurp(dir + "/out/" + plot);
        EXPECT_EQ(svg.find("<script"), std::string::npos) << plot;
        const auto texts = svg_texts(svg);
        ASSERT_TRUE(texts.has_value()) << plot << " is not well-formed:\n" << svg;
        EXPECT_NE(std::find_if(texts->begin(), texts->end(),
                               [&](const std::string& t) { return t.rfind(name + ": frames/s against", 0) == 0; }),
                  texts->end())
            << plot;
        // Each point's title is its id, the control character shown as U+FFFD.
        const std::string b = "surf.source=" + (fs::canonical(dir) / "<script>a & 'b'.png").string();
        const std::string d = "surf.source=" + (fs::canonical(dir) / "c\"d<e>\xEF\xBF\xBD.png").string();
        for (const std::string& id : {b, d})
            EXPECT_NE(std::find_if(texts->begin(), texts->end(),
                                   [&](const std::string& t) { return t.rfind(id + ":", 0) == 0; }),
                      texts->end())
                << plot << ": no point titled " << id;
    }
}

// Runs `sql` on the database `file`.
void sql(const std::string& file, const std::string& statements) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
    char* message = nullptr;
    EXPECT_EQ(sqlite3_exec(db, statements.c_str(), nullptr, nullptr, &message), SQLITE_OK) << (message ? message : "");
    sqlite3_free(message);
    sqlite3_close(db);
}

// A damaged sweep.db (not SQLite, cut short, other tables, rows whose values are not what a
// sweep writes) is bad input naming the file and the point: exit 2, before any point runs,
// never exit 3.
TEST(Sweep, ADamagedDatabaseIsBadInputNamingTheFileAndThePoint) {
    const std::string dir = fresh_dir("damaged");
    const std::string file = smoke_sweep(dir, kTinyAxes);
    ASSERT_EQ(surfvp("sweep " + file + " --quiet --out " + dir + "/good").exit_code, 0);
    const std::string good = slurp(dir + "/good/sweep.db");
    const std::string db = dir + "/out/sweep.db";
    auto refused = [&](const std::string& what, const std::function<void()>& damage, const std::string& message) {
        fs::remove_all(dir + "/out");
        fs::create_directories(dir + "/out");
        write_file(dir + "/out", "sweep.db", good);
        damage();
        const auto r = surfvp("sweep " + file + " --out " + dir + "/out");
        EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
        EXPECT_NE(r.err.find("surfvp: error: " + db + ": " + message), std::string::npos) << what << ": " << r.err;
        EXPECT_EQ(r.err.find("points run"), std::string::npos) << what << ": " << r.err;
    };
    refused(
        "not SQLite", [&] { write_file(dir + "/out", "sweep.db", "name: not a database\n"); },
        "not a sweep database, or a damaged one");
    refused(
        "cut short", [&] { write_file(dir + "/out", "sweep.db", good.substr(0, good.size() / 2)); },
        "not a sweep database, or a damaged one");
    refused(
        "an index without a row",
        [&] {  // SQLite reads through it (found by tests/fuzz sweep_db)
            fs::copy_file(std::string(SURFVP_SOURCE_DIR) + "/tests/fuzz/regressions/sweep_db/index_missing_a_row", db,
                          fs::copy_options::overwrite_existing);
        },
        "not a sweep database, or a damaged one (integrity check: row 2 missing from index");
    refused(
        "other tables", [&] { sql(db, "DROP TABLE points; CREATE TABLE points (a, b);"); },
        "is not a sweep database: its table points has the columns (a, b), not (idx, id, params, exit, error, figures, "
        "wall_s)");
    refused(
        "another program's database",
        [&] {
            fs::remove(db);
            sql(db, "CREATE TABLE t (x);");
        },
        "is not a sweep database: it holds a table 't' a sweep's has not");
    const std::string point1 = "point 1 (plb2.width=64 bit): ";
    refused(
        "params not JSON", [&] { sql(db, "UPDATE points SET params = '{\"plb2.width\": ' WHERE idx = 1"); },
        point1 + "params is not JSON: [json.exception.parse_error.101]");
    refused(
        "params a list", [&] { sql(db, "UPDATE points SET params = '[1]' WHERE idx = 1"); },
        point1 + "params is a JSON array, not an object");
    refused(
        "a value a number", [&] { sql(db, "UPDATE points SET params = '{\"plb2.width\": 64}' WHERE idx = 1"); },
        point1 + "params.plb2.width is a JSON number, not a text");
    refused(
        "figures a text", [&] { sql(db, "UPDATE points SET figures = '\"fast\"' WHERE idx = 1"); },
        point1 + "figures is a JSON string, not an object");
    refused(
        "frames/s a text", [&] { sql(db, "UPDATE points SET figures = '{\"fps\": \"fast\"}' WHERE idx = 1"); },
        point1 + "figures.fps is a JSON string, not a number");
    refused(
        "exit not an exit code", [&] { sql(db, "UPDATE points SET exit = 1000 WHERE idx = 1"); },
        point1 + "exit 1000 is not an exit code");
    refused(
        "index a text", [&] { sql(db, "UPDATE points SET idx = 'one' WHERE id = 'plb2.width=64 bit'"); },
        "point in row ");
    EXPECT_NE(surfvp("sweep " + file + " --out " + dir + "/out")
                  .err.find(" (plb2.width=64 bit): its idx is text, not an integer"),
              std::string::npos);
}

// Every file of a folder, by name, with its content.
std::map<std::string, std::string> files_in(const std::string& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out[e.path().filename().string()] = slurp(e.path().string());
    return out;
}

// sweep-merge reads and checks everything before it writes: an empty, foreign, not-SQLite or
// damaged database, a missing shard or no shard at all is refused (exit 2, naming the file and
// the point), and the folder's sweep.db, results and plots are left as they were, with
// nothing beside them.
TEST(SweepMerge, RefusesWhatItCannotMergeAndLeavesTheFolderAsItWas) {
    const std::string dir = fresh_dir("merge");
    const std::string file = smoke_sweep(dir, kTinyAxes), out = dir + "/out";
    for (const char* shard : {"1/2", "2/2"})
        ASSERT_EQ(surfvp("sweep " + file + " --quiet --shard " + shard + " --out " + out).exit_code, 0) << shard;
    ASSERT_EQ(surfvp("sweep-merge " + out).exit_code, 0);
    const std::string shard1 = slurp(out + "/shard-1-of-2.db"), shard2 = slurp(out + "/shard-2-of-2.db");
    // Another sweep's shard 2.
    const std::string other = write_file(dir, "other.yaml",
                                         "scenario: base.yaml\nset: {smoke.copies: 2, surf.source: frame.png}\n"
                                         "axes:\n  plb2.width: [32 bit, 128 bit]\n");
    ASSERT_EQ(surfvp("sweep " + other + " --quiet --shard 2/2 --out " + dir + "/other").exit_code, 0);

    auto refused = [&](const std::string& what, const std::function<void()>& damage, const std::string& message,
                       const std::string& args = "") {
        write_file(out, "shard-1-of-2.db", shard1);
        write_file(out, "shard-2-of-2.db", shard2);
        damage();
        const auto before = files_in(out);
        const auto r = surfvp("sweep-merge " + out + args);
        EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
        EXPECT_NE(r.err.find("surfvp: error: " + message), std::string::npos) << what << ": " << r.err;
        EXPECT_EQ(files_in(out), before) << what;
    };
    const std::string s2 = out + "/shard-2-of-2.db";
    refused(
        "empty", [&] { write_file(out, "shard-2-of-2.db", ""); }, s2 + ": is empty: it holds no sweep");
    refused(
        "foreign", [&] { fs::copy_file(dir + "/other/shard-2-of-2.db", s2, fs::copy_options::overwrite_existing); },
        s2 + ": is not of the sweep of " + out +
            "/sweep.db: axis plb2.width: values changed (32 bit, 64 bit; now 32 bit, 128 bit)");
    refused(
        "not SQLite", [&] { write_file(out, "shard-2-of-2.db", "shard\n"); },
        s2 + ": not a sweep database, or a damaged one");
    refused(
        "damaged row", [&] { sql(s2, "UPDATE points SET figures = '{' WHERE idx = 1"); },
        s2 + ": point 1 (plb2.width=64 bit): figures is not JSON");
    refused(
        "values not the id",
        [&] { sql(s2, "UPDATE points SET params = '{\"plb2.width\": \"16 bit\"}' WHERE idx = 1"); },
        s2 + ": point 1 (plb2.width=64 bit): its values give another id (plb2.width=16 bit)");
    refused(
        "damaged axes", [&] { sql(s2, "UPDATE sweep SET value = '[\"../../x\"]' WHERE key = 'axes'"); },
        s2 + ": its record of the sweep's axes is damaged");
    refused(
        "renamed", [&] { write_file(out, "shard-2-of-2.db", shard1); },
        s2 + ": point 0 (plb2.width=32 bit) is not of shard 2 of 2");
    refused(
        "damaged sweep.db",
        [&] {
            write_file(out, "sweep.db.keep", slurp(out + "/sweep.db"));
            write_file(out, "sweep.db", "x");
        },
        out + "/sweep.db: not a sweep database, or a damaged one");
    write_file(out, "sweep.db", slurp(out + "/sweep.db.keep"));
    fs::remove(out + "/sweep.db.keep");
    refused(
        "missing", [&] { fs::remove(s2); },
        out +
            ": shard 2 of 2 is missing (shard-2-of-2.db): their points would not be in "
            "the results; give --partial");
    refused(
        "no shards",
        [&] {
            fs::remove(s2);
            fs::remove(out + "/shard-1-of-2.db");
        },
        out + ": holds no shard databases (shard-K-of-N.db) to merge");

    const auto a_file = surfvp("sweep-merge " + file);
    EXPECT_EQ(a_file.exit_code, 2) << a_file.err;
    EXPECT_NE(a_file.err.find(file + ": not a folder (give the sweep's --out folder)"), std::string::npos)
        << a_file.err;

    // A point a shard ran replaces the same point that sweep.db has as not run (a shard run
    // again); a point no database ran makes the merge exit 1, named.
    write_file(out, "shard-1-of-2.db", shard1);
    write_file(out, "shard-2-of-2.db", shard2);
    sql(out + "/sweep.db", "UPDATE points SET exit = 3, error = 'killed', figures = '{}' WHERE idx = 1");
    const auto rerun = surfvp("sweep-merge " + out);
    EXPECT_EQ(rerun.exit_code, 0) << rerun.err;
    EXPECT_EQ(results(out)["points"][1]["status"], "passed");
    for (const std::string& db : {out + "/sweep.db", s2})
        sql(db, "UPDATE points SET exit = 3, error = 'killed' WHERE idx = 1");
    const auto killed = surfvp("sweep-merge " + out);
    EXPECT_EQ(killed.exit_code, 1) << killed.err;
    EXPECT_NE(killed.err.find("1 points could not run: point 1 (plb2.width=64 bit, exit 3)"), std::string::npos)
        << killed.err;
    EXPECT_EQ(results(out)["points"][1]["status"], "error");

    // --partial merges the shards there are and says which are missing.
    const std::string part = dir + "/part";
    ASSERT_EQ(surfvp("sweep " + file + " --quiet --shard 1/3 --out " + part).exit_code, 0);
    ASSERT_EQ(surfvp("sweep " + file + " --quiet --shard 3/3 --out " + part).exit_code, 0);  // no point of its own
    const auto r = surfvp("sweep-merge " + part + " --partial");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("2 shard databases, 1 new points, 1 in all; results in " + part +
                         " (partial: shard 2 of 3 is missing (shard-2-of-3.db), their points are not in the results)"),
              std::string::npos)
        << r.err;
    const Json j = results(part);
    EXPECT_EQ(j["missing_shards"], Json::array({"shard-2-of-3.db"}));
    ASSERT_EQ(j["points"].size(), 1u);
    EXPECT_EQ(j["points"][0]["point"], 0);
    for (const auto& e : fs::directory_iterator(part))  // the merged database went into place under its name
        EXPECT_EQ(e.path().filename().string().find(".sweep.db"), std::string::npos) << e.path();
}

TEST(Sweep, BadShardOptionsAreBadInput) {
    const std::string dir = fresh_dir("bad_shard");
    const std::string file = small_sweep(dir, kTwoByTwo);
    for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
             {" --shard 3/2", "expected K/N with 1 <= K <= N"},
             {" --shard 0/2", "expected K/N"},
             {" --shard two", "expected K/N"},
             {" --slurm 2 --shard 1/2", "give --slurm or --shard, not both"}}) {
        const auto r = surfvp("sweep " + file + " --out " + dir + "/out" + args);
        EXPECT_EQ(r.exit_code, 2) << args;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    }
}

}  // namespace
}  // namespace surfvp::test
