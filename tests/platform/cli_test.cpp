// The surfvp command line end to end, as an architect uses it.
#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli.h"
#include "platform/scenario/parameters.h"
#include "vcd_reader.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;
using test::fresh_dir;
using test::slurp;
using test::surfvp;

const std::string kSmoke = std::string(SURFVP_SOURCE_DIR) + "/scenarios/smoke.yaml";

// surfvp starts without OpenCV's codec libraries (~240 shared libraries, ~0.2 s to load): only
// its image and video plugin, beside it, links them (sw/media/media.h).
TEST(Cli, StartsWithoutTheCodecLibraries) {
    const std::string listing = fresh_dir("needed") + "/needed.txt";
    ASSERT_EQ(std::system(("readelf -d " + std::string(SURFVP_BINARY) + " > " + listing).c_str()), 0);
    const std::string needed = slurp(listing);
    EXPECT_NE(needed.find("libopencv_core"), std::string::npos);
    EXPECT_EQ(needed.find("libopencv_imgcodecs"), std::string::npos);
    EXPECT_EQ(needed.find("libopencv_videoio"), std::string::npos);
    const fs::path plugin = fs::path(SURFVP_BINARY).parent_path() / "libsurfvp_media.so";
    ASSERT_TRUE(fs::exists(plugin));
    ASSERT_EQ(std::system(("readelf -d " + plugin.string() + " > " + listing).c_str()), 0);
    EXPECT_NE(slurp(listing).find("libopencv_imgcodecs"), std::string::npos);
}

TEST(Cli, SmokeRunWritesReportsAndTraces) {
    const std::string out = fresh_dir("smoke");
    const auto r = surfvp("run " + kSmoke + " --out " + out + " --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "") << "--quiet prints nothing";
    for (const char* f : {"report.json", "report.md", "config.yaml", "trace.vcd", "trace.perfetto.json"})
        EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
    for (const auto& entry : fs::directory_iterator(out))
        EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();

    const auto report = nlohmann::json::parse(slurp(out + "/report.json"));
    const uint64_t moved = 64 * 1024 * 4;  // smoke.buffer x smoke.copies
    EXPECT_TRUE(report["passed"].get<bool>());
    EXPECT_EQ(report["workload"]["bytes_copied"].get<uint64_t>(), moved);
    EXPECT_EQ(report["buses"]["plb2"]["masters"]["dma"]["bytes_read"].get<uint64_t>(), moved);
    EXPECT_EQ(report["buses"]["plb2"]["masters"]["dma"]["bytes_written"].get<uint64_t>(), moved);
    EXPECT_EQ(report["memory"]["ports"]["plb2"]["bytes_written"].get<uint64_t>(), moved);
    EXPECT_GT(report["buses"]["plb1"]["read"]["bursts"].get<uint64_t>(), 0u);  // the CPU's polls
    EXPECT_GT(report["buses"]["plb2"]["write"]["utilisation"].get<double>(), 0.0);
    EXPECT_GT(report["sim_time_s"].get<double>(), 0.0);
    EXPECT_GT(report["real_time_factor"].get<double>(), 0.0);
}

TEST(Cli, SmokeVcdHasBusyLinesAndInterrupts) {
    const std::string out = fresh_dir("vcd");
    ASSERT_EQ(surfvp("run " + kSmoke + " --out " + out + " --quiet --trace vcd").exit_code, 0);
    EXPECT_FALSE(fs::exists(out + "/trace.perfetto.json"));
    const auto vcd = test::Vcd::read(out + "/trace.vcd");
    EXPECT_EQ(vcd.timescale, "1ps");
    for (const char* s : {"plb1.read_busy", "plb1.write_busy", "plb2.read_busy", "plb2.write_busy", "dma.busy",
                          "irq.dma", "irq.cpu", "cpu.waiting_irq"})
        ASSERT_TRUE(vcd.changes.count(s)) << s;
    EXPECT_EQ(vcd.rises("irq.dma"), 4u);  // one per copy
    EXPECT_EQ(vcd.rises("irq.cpu"), 4u);
    EXPECT_EQ(vcd.rises("dma.busy"), 4u);
    EXPECT_GT(vcd.rises("plb2.write_busy"), 0u);
    EXPECT_GT(vcd.rises("plb1.read_busy"), 0u);
    // Its GTKWave save file shows every traced signal and names the files by absolute path.
    const std::string gtkw = slurp(out + "/trace.gtkw");
    for (const auto& [name, changes] : vcd.changes) EXPECT_NE(gtkw.find("SystemC." + name), std::string::npos) << name;
    EXPECT_NE(gtkw.find("[dumpfile] \"" + fs::absolute(out).string() + "/trace.vcd\""), std::string::npos) << gtkw;
    EXPECT_EQ(slurp(out + "/trace.tasks.txt"), "4294967295 none\n");
}

TEST(Cli, SmokePerfettoTraceIsValidJsonWithTracksAndSlices) {
    const std::string out = fresh_dir("perfetto");
    ASSERT_EQ(surfvp("run " + kSmoke + " --out " + out + " --quiet --trace perfetto").exit_code, 0);
    EXPECT_FALSE(fs::exists(out + "/trace.vcd"));
    const auto trace = nlohmann::json::parse(slurp(out + "/trace.perfetto.json"));
    std::set<std::string> tracks;
    size_t dma_bursts = 0, bus_bursts = 0, cpu_spans = 0, counters = 0;
    std::map<int, std::string> processes;
    for (const auto& e : trace["traceEvents"]) {
        if (e["ph"] == "M" && e["name"] == "process_name") processes[e["pid"]] = e["args"]["name"];
        if (e["ph"] == "M" && e["name"] == "thread_name") tracks.insert(e["args"]["name"].get<std::string>());
        const bool burst = e["ph"] == "X" && e.contains("args") && e["args"].value("bytes", 0.0) == 256;
        if (burst && e["name"] == "write") ++dma_bursts;      // the master's track
        if (burst && e["name"] == "dma write") ++bus_bursts;  // the bus's write-data track
        if (e["ph"] == "X" && processes[e["pid"]] == "cpu") ++cpu_spans;
        if (e["ph"] == "C") ++counters;
    }
    for (const char* t : {"cpu", "dma read", "dma write", "read data", "write data"}) EXPECT_TRUE(tracks.count(t)) << t;
    EXPECT_EQ(dma_bursts, 4u * 256);  // 256 bursts per 64 KiB copy
    EXPECT_EQ(bus_bursts, 4u * 256);
    EXPECT_GT(cpu_spans, 4u * 4);
    EXPECT_GT(counters, 0u);
}

// A progress line is for a terminal: in a pipe a run says only its last line, unless asked
// (--progress), then a line of its own every half second with the fixed total and the time to go.
TEST(Cli, LongRunsShowProgressOnATerminalOrWhenAsked) {
    // ~2 s of wall time: 6000 copies of 64 KiB without traces.
    const std::string run = "run smoke --trace none --set smoke.copies=6000 --out " + fresh_dir("progress");
    const auto piped = surfvp(run);
    ASSERT_EQ(piped.exit_code, 0) << piped.err;
    EXPECT_EQ(piped.err.rfind("surfvp: smoke: passed; ", 0), 0u) << piped.err;  // the one line
    const auto asked = surfvp(run + " --progress");
    ASSERT_EQ(asked.exit_code, 0) << asked.err;
    const std::regex line(
        R"(surfvp: smoke: \[[#.]{24}\] (\d+)/6000 copies, [0-9.]+ ms simulated, \d+:\d\d gone, \d+:\d\d to go\n)");
    const auto lines =
        std::distance(std::sregex_iterator(asked.err.begin(), asked.err.end(), line), std::sregex_iterator());
    EXPECT_GE(lines, 1) << asked.err;
    EXPECT_NE(asked.err.find("surfvp: smoke: passed; "), std::string::npos) << asked.err;
}

TEST(Cli, SameScenarioGivesTheSameBytes) {
    const std::string a = fresh_dir("a"), b = fresh_dir("b");
    ASSERT_EQ(surfvp("run " + kSmoke + " --out " + a + " --quiet").exit_code, 0);
    ASSERT_EQ(surfvp("run " + kSmoke + " --out " + b + " --quiet").exit_code, 0);
    EXPECT_EQ(slurp(a + "/trace.perfetto.json"), slurp(b + "/trace.perfetto.json"));
    EXPECT_EQ(slurp(a + "/config.yaml"), slurp(b + "/config.yaml"));
    // VCD: all but SystemC's $date header; reports: all but the fields they list as wall-clock.
    const std::regex date(R"(\$date[^$]*\$end)");
    EXPECT_EQ(std::regex_replace(slurp(a + "/trace.vcd"), date, ""),
              std::regex_replace(slurp(b + "/trace.vcd"), date, ""));
    auto ja = nlohmann::json::parse(slurp(a + "/report.json")), jb = nlohmann::json::parse(slurp(b + "/report.json"));
    for (const auto& field : ja["wall_clock_fields"]) {
        ja.erase(field.get<std::string>());
        jb.erase(field.get<std::string>());
    }
    EXPECT_EQ(ja, jb);
}

TEST(Cli, ValidateNamesTheMisspeltKeyAndLine) {
    const std::string dir = fresh_dir("validate");
    const std::string path = test::write_file(dir, "bad.yaml", "name: bad\nplb2:\n  width: 64 bit\n  clokc: 100 MHz\n");
    const auto r = surfvp("validate " + path);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(path + ":4"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("plb2.clokc"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("did you mean 'plb2.clock'"), std::string::npos) << r.err;
}

TEST(Cli, ValidateAcceptsAGoodScenario) {
    const auto r = surfvp("validate " + kSmoke + " --set 'plb2.width=64 bit'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("ok"), std::string::npos);
    EXPECT_NE(r.out.find("1 from --set"), std::string::npos) << r.out;
}

TEST(Cli, BadInputWritesNothingAndKeepsWhatWasThere) {
    const std::string out = fresh_dir("keep");
    test::write_file(out, "report.json", "earlier run");
    const auto r = surfvp("run " + kSmoke + " --out " + out + " --set 'plb2.width=100 MHz'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("plb2.width"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(out + "/report.json"), "earlier run");
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator{}), 1);
}

TEST(Cli, BufferOutsideMemoryIsBadInput) {
    const auto r = surfvp("run smoke --out " + fresh_dir("outside") + " --set smoke.dst=0x0FFF_F000");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("smoke.dst"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("memory.size"), std::string::npos) << r.err;
}

TEST(Cli, UnknownCommandOrOptionIsBadInput) {
    EXPECT_EQ(surfvp("frobnicate").exit_code, 2);
    EXPECT_EQ(surfvp("run " + kSmoke + " --tracing all").exit_code, 2);
    EXPECT_EQ(surfvp("run " + kSmoke + " --trace some").exit_code, 2);
}

TEST(Cli, ListShowsShippedScenariosWithDescriptions) {
    const auto r = surfvp("list");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("smoke"), std::string::npos);
    EXPECT_NE(r.out.find("test DMA"), std::string::npos) << r.out;
}

TEST(Cli, VersionAndHelp) {
    EXPECT_NE(surfvp("--version").out.find("surfvp 0."), std::string::npos);
    for (const char* command : {"run", "validate", "list", "params"}) {
        const auto r = surfvp(std::string(command) + " --help");
        EXPECT_EQ(r.exit_code, 0) << command;
        EXPECT_NE(r.out.find("Usage"), std::string::npos) << command;
    }
}

TEST(Cli, ParameterDocMatchesTheTable) {
    const auto r = surfvp("params");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, parameters_markdown());
    EXPECT_EQ(slurp(std::string(SURFVP_SOURCE_DIR) + "/docs/parameters.md"), r.out)
        << "docs/parameters.md is stale: regenerate it with `build/surfvp params > docs/parameters.md`";
}

}  // namespace
}  // namespace surfvp

namespace surfvp {
namespace {

TEST(Cli, SeqgenPrintsTheThreeSchedulesAndTheImpliedFrameRate) {
    const auto r = test::surfvp("seqgen --width 1024 --height 768");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["reads_per_block"], 576);
    EXPECT_EQ(j["distinct_reads_per_block"], 405);
    EXPECT_EQ(j["optimal"]["cycles_per_block"], 48);
    EXPECT_EQ(j["machine"]["line_fifo"], "tdp_x2");
    EXPECT_EQ(j["machine"]["bus_word_bits"], 128);
    const int basic = j["basic"]["cycles_per_block"], improved = j["improved"]["cycles_per_block"];
    EXPECT_GE(basic, improved);
    EXPECT_GE(improved, 48);
    EXPECT_EQ(j["scheduler"], "basic");
    const int cycles = j["cycles_per_block"];
    EXPECT_EQ(cycles, basic);  // the chip runs the basic script by default
    EXPECT_NEAR(j["frame"]["frames_per_second"].get<double>(), 100e6 / (512.0 * 384 * cycles), 1e-9);
    EXPECT_NEAR(j["basic"]["overhead"].get<double>(), basic / 48.0 - 1, 1e-12);
    // The paper's note 4: against the words the basic script carries, 192 over 4 buses.
    EXPECT_EQ(j["basic"]["busy_bus_cycles"], 48);
    EXPECT_NEAR(j["basic"]["idle_bus_overhead"].get<double>(), basic / 48.0 - 1, 1e-12);
}

TEST(Cli, SeqgenFollowsParameters) {
    const auto scalar = nlohmann::json::parse(test::surfvp("seqgen --set fhg.bus_word=scalar --set fhg.reuse=off").out);
    EXPECT_EQ(scalar["optimal"]["cycles_per_block"], 144);  // 576 reads over 4 buses
    EXPECT_EQ(scalar["improved"]["cycles_per_block"], 144);
    const auto improved = nlohmann::json::parse(test::surfvp("seqgen --set fhg.scheduler=improved").out);
    EXPECT_EQ(improved["cycles_per_block"], improved["improved"]["cycles_per_block"]);
    const auto forced = nlohmann::json::parse(test::surfvp("seqgen --set 'fhg.cycles_per_block=50 cycles'").out);
    EXPECT_EQ(forced["cycles_per_block"], 50);
    EXPECT_EQ(forced["block_limit"], "fhg.cycles_per_block");
    const auto six = nlohmann::json::parse(test::surfvp("seqgen --set fhg.bus_word=scalar --set fhg.read_buses=6").out);
    EXPECT_LT(six["improved"]["cycles_per_block"].get<int>(), 103);
    EXPECT_GE(six["improved"]["cycles_per_block"].get<int>(), six["optimal"]["cycles_per_block"].get<int>());
    for (const char* bad : {"fhg.fifo_lines=40", "fhg.line_fifo=sdp72", "fhg.line_fifo=quad"}) {
        const auto r = test::surfvp(std::string("seqgen --set ") + bad);
        EXPECT_EQ(r.exit_code, 2) << bad;
        EXPECT_NE(r.err.find(std::string(bad).substr(0, std::string(bad).find('='))), std::string::npos) << r.err;
    }
}

TEST(Cli, RegisterDocMatchesTheTables) {
    const auto r = surfvp("registers");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("| 0x28 | OVERFLOW_COUNT | RO | 0x0 |"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("| 1 | DONE | W1C |"), std::string::npos);
    EXPECT_EQ(slurp(std::string(SURFVP_SOURCE_DIR) + "/docs/registers.md"), r.out)
        << "docs/registers.md is stale: regenerate it with `build/surfvp registers > docs/registers.md`";
}

// `surfvp bench` on the smoke scenario (quick): every figure and target is there; the
// start-up is the runs' own (report.json startup_s); a scenario that does not exist is bad
// input. The figures themselves are for the notes (tests/bench), not for a test.
TEST(Cli, BenchGivesTheFiguresAndTheTargets) {
    const auto r = test::surfvp("bench smoke --frames 1");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* traces : {"traces_none", "traces_all"})
        for (const char* key : {"wall_per_frame_ms", "startup_ms", "peak_rss_mb", "real_time_factor"})
            EXPECT_TRUE(j[traces].contains(key)) << traces << " " << key;
    EXPECT_GT(j["traces_none"]["startup_ms"].get<double>(), 0.0);
    EXPECT_LT(j["traces_none"]["startup_ms"].get<double>(), 10000.0);
    EXPECT_GT(j["traces_none"]["peak_rss_mb"].get<double>(), 1.0);
    for (const char* target :
         {"wall_per_frame_ms", "traces_all_over_none", "startup_ms", "peak_rss_mb", "real_time_factor"})
        EXPECT_TRUE(j["targets"][target].contains("met")) << target;
    EXPECT_FALSE(j.contains("float_reference"));  // the smoke scenario runs no SURF
    EXPECT_FALSE(j.contains("direct"));           // nor direct mode, which runs SURF only
    EXPECT_EQ(test::surfvp("bench no_such_scenario").exit_code, 2);
}

// On a SURF scenario `surfvp bench` also runs direct mode the same way (runs of N frames timed
// by their own frames, their startup_s) and holds the VP's time per frame over direct mode's to
// its target: the median of the rounds' own ratios (each round runs both modes in turn); and
// the same ratio of whole runs.
TEST(Cli, BenchOnASurfScenarioGivesDirectModesFiguresAndItsSpeedUp) {
    const auto r = test::surfvp("bench budget_1024x768 --frames 2");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"wall_per_frame_ms", "startup_ms", "peak_rss_mb"})
        EXPECT_GT(j["direct"][key].get<double>(), 0.0) << key;
    EXPECT_FALSE(j["direct"].contains("real_time_factor"));  // direct mode has no time
    const auto& speed_up = j["targets"]["vp_over_direct"];
    EXPECT_EQ(speed_up["target"].get<double>(), 3.0);
    const auto vp = j["traces_none"]["per_round_ms"], direct = j["direct"]["per_round_ms"];
    ASSERT_EQ(vp.size(), 3u);
    ASSERT_EQ(direct.size(), 3u);
    std::vector<double> ratios;
    for (size_t k = 0; k < 3; ++k) ratios.push_back(vp[k].get<double>() / direct[k].get<double>());
    std::sort(ratios.begin(), ratios.end());
    EXPECT_DOUBLE_EQ(speed_up["value"].get<double>(), ratios[1]);
    EXPECT_EQ(speed_up["met"].get<bool>(), speed_up["value"].get<double>() >= 3.0);
    for (const char* mode : {"traces_none", "direct"}) {  // the fastest round's
        double fastest = 1e9;
        for (const auto& ms : j[mode]["per_round_ms"]) fastest = std::min(fastest, ms.get<double>());
        EXPECT_DOUBLE_EQ(j[mode]["wall_per_frame_ms"].get<double>(), fastest) << mode;
    }
    // Whole runs too: each takes longer than its own start-up (the fastest of each are given).
    for (const char* mode : {"traces_none", "traces_all", "direct"})
        EXPECT_GT(j[mode]["whole_run_ms"].get<double>(), j[mode]["startup_ms"].get<double>()) << mode;
    const auto& whole = j["targets"]["vp_over_direct_whole_run"];
    EXPECT_EQ(whole["target"].get<double>(), 3.0);
    EXPECT_GT(whole["value"].get<double>(), 0.0);
    EXPECT_EQ(whole["met"].get<bool>(), whole["value"].get<double>() >= 3.0);
    EXPECT_GT(j["float_reference"]["ms_per_frame"].get<double>(), 0.0);
}

// A SURF run's report gives the host's wall-clock time at which each frame was reported (from
// the software's start, in the order they were), in the VP and in direct mode, as a wall-clock
// field: `surfvp bench` reads its time per frame off them.
TEST(Cli, ARunsReportTimesItsFramesOnTheWallClock) {
    for (const std::string mode : {"", " --direct"}) {
        const std::string out = fresh_dir("frame_wall" + std::to_string(mode.size()));
        const auto r = surfvp(
            "run budget_1024x768 --quiet --trace none --set surf.frames=4 --set budget.fps=0 --set verdict.band=off "
            "--set verdict.break_even=off --set verdict.software=off --out " +
            out + mode);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const auto j = nlohmann::json::parse(slurp(out + "/report.json"));
        const auto times = j["frame_wall_s"].get<std::vector<double>>();
        ASSERT_EQ(times.size(), 4u) << mode;
        EXPECT_GT(times[0], 0.0) << mode;
        EXPECT_TRUE(std::is_sorted(times.begin(), times.end())) << mode;
        EXPECT_LE(times.back(), j["wall_time_s"].get<double>()) << mode;
        const auto fields = j["wall_clock_fields"].get<std::vector<std::string>>();
        EXPECT_NE(std::find(fields.begin(), fields.end(), "frame_wall_s"), fields.end()) << mode;
    }
}

}  // namespace
}  // namespace surfvp

namespace surfvp::test {
namespace {

// --quick: the default scenario as one run. Its report has the frame rate and the limit but no
// verdict (none of its re-simulations ran); config.yaml says which settings --quick turned off.
// A --set that asks for one of them contradicts it: bad input, nothing written.
TEST(Cli, QuickRunsTheScenarioWithoutTheVerdictsResimulations) {
    const std::string out = fresh_dir("quick");
    const auto r = surfvp("run budget_1024x768 --quick --trace none --set surf.frames=3 --out " + out);
    EXPECT_EQ(r.exit_code, 1) << r.err;  // 3 frames of the default scenario miss its 10 frames/s
    const auto j = nlohmann::json::parse(slurp(out + "/report.json"));
    EXPECT_FALSE(j.contains("verdict"));
    EXPECT_GT(j["throughput_fps"].get<double>(), 5.0);
    EXPECT_EQ(j["limit"]["resource"].get<std::string>(), "fhg");
    const std::string yaml = slurp(out + "/config.yaml");
    for (const char* key : {"break_even", "band", "software"})
        EXPECT_NE(yaml.find(std::string(key) + ": off  # --quick"), std::string::npos) << key;

    const std::string refused = fresh_path("quick_refused");
    const auto both = surfvp("run budget_1024x768 --quick --set verdict.band=on --out " + refused);
    EXPECT_EQ(both.exit_code, 2);
    EXPECT_NE(both.err.find("--set verdict.band=on"), std::string::npos) << both.err;
    EXPECT_FALSE(std::filesystem::exists(refused));
}

// The terminal's last line gives the answer as report.md's first line does: passed or FAILED,
// the verdict's statement (frames/s, margin, the limit and its cause, the break-even), and the
// whole wall time, the verdict's re-simulations included.
TEST(Cli, TheLastLineGivesTheAnswerAndTheWholeWallTime) {
    const std::string out = fresh_dir("last_line");
    const auto r = surfvp(
        "run budget_1024x768 --trace none --set surf.frames=4 --set verdict.band=off "
        "--set verdict.software=off --out " +
        out);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    const std::string err = r.err.substr(0, r.err.size() - 1);
    const std::string last = err.substr(err.rfind('\n') + 1);
    const auto j = nlohmann::json::parse(slurp(out + "/report.json"));
    const std::string statement = j["verdict"]["statement"].get<std::string>();
    EXPECT_EQ(last.rfind("surfvp: budget_1024x768: FAILED: Verdict: " + statement + "; ", 0), 0u) << last;
    EXPECT_NE(statement.find("missed at defaults ("), std::string::npos) << statement;
    EXPECT_NE(statement.find("% against 10); limited by fhg (busy); break-even fhg.clock = "), std::string::npos)
        << statement;
    EXPECT_NE(slurp(out + "/report.md").find("**Verdict: " + statement + ".**"), std::string::npos);
    const std::smatch wall = [&] {
        std::smatch m;
        std::regex_search(last, m, std::regex(R"(; ([0-9.]+) ms simulated, ([0-9.]+) s wall in all; report in )"));
        return m;
    }();
    ASSERT_EQ(wall.size(), 3u) << last;
    EXPECT_GT(std::stod(wall[2].str()), j["wall_time_s"].get<double>() - 0.05);  // the whole, not the one run
}

// A missed budget and a run that broke end differently: 1 is the design's answer, 6 says the
// run itself failed (here the maxima FIFO, four deep, overflows and both frames are lost).
TEST(Cli, AMissedBudgetAndABrokenRunHaveTheirOwnExitCodes) {
    REQUIRE_OPENCV_DATA("graf1.png");
    const std::string missed = fresh_dir("exit_missed"), broken = fresh_dir("exit_broken");
    const auto slow = surfvp("run graf --quick --trace none --set budget.fps=1000 --out " + missed);
    EXPECT_EQ(slow.exit_code, 1) << slow.err;
    const auto m = nlohmann::json::parse(slurp(missed + "/report.json"));
    EXPECT_FALSE(m["passed"].get<bool>());
    EXPECT_FALSE(m["broken"].get<bool>());
    EXPECT_NE(slow.err.find("surfvp: graf: FAILED: "), std::string::npos) << slow.err;
    // The evaluation's figures in words, no JSON in a table cell.
    const std::string md = slurp(missed + "/report.md");
    EXPECT_EQ(md.find("{\""), std::string::npos);
    EXPECT_NE(md.find("| evaluation | homography (repeatability 0."), std::string::npos);

    for (const std::string mode : {"--direct", "--quick --trace none"}) {
        const auto r = surfvp("run graf " + mode + " --set fhg.maxima_fifo_depth=4 --out " + broken);
        EXPECT_EQ(r.exit_code, 6) << mode << r.err;
        const auto b = nlohmann::json::parse(slurp(broken + "/report.json"));
        EXPECT_TRUE(b["broken"].get<bool>()) << mode;
        EXPECT_EQ(b["checks"][0]["kind"], "run");
        EXPECT_FALSE(b["checks"][0]["passed"].get<bool>());
        EXPECT_NE(r.err.find("BROKEN"), std::string::npos) << mode << r.err;
        EXPECT_NE(r.err.find("the maxima FIFO overflowed"), std::string::npos) << mode << r.err;
    }
    EXPECT_NE(slurp(broken + "/report.md")
                  .find("**The run broke: every frame processed failed: frame 0: the maxima "
                        "FIFO overflowed: "),
              std::string::npos);
}

}  // namespace
}  // namespace surfvp::test
