// The trace writers: files appear under their final names only when finished, and the
// timeline is valid JSON whatever the names hold.
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>

#include "models/common/tracer.h"
#include "platform/cli.h"

namespace surfvp {
namespace {
namespace fs = std::filesystem;

std::string temp_dir(const std::string& name) {
    const auto dir = fs::temp_directory_path() / ("surfvp_tracer_" + std::to_string(::getpid())) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

TEST(Tracer, TimelineIsValidJsonWithEscapedNamesAndPicosecondTimes) {
    const std::string dir = temp_dir("json");
    {
        Tracer tracer({false, true, dir});
        const int track = tracer.track("group \"g\"", "track\\1");
        tracer.slice(track, "say \"hi\"\n", sc_core::sc_time(1.5, sc_core::SC_NS), sc_core::sc_time(2, sc_core::SC_US));
        tracer.counter(track, "level", sc_core::sc_time(3, sc_core::SC_PS), 7);
        EXPECT_FALSE(fs::exists(dir + "/trace.perfetto.json"));
        tracer.finish();
    }
    std::ifstream in(dir + "/trace.perfetto.json");
    const auto json = nlohmann::json::parse(in);
    const auto& events = json["traceEvents"];
    bool slice = false, counter = false, names = false;
    for (const auto& e : events) {
        if (e["ph"] == "X") {
            slice = true;
            EXPECT_EQ(e["name"], "say \"hi\"\n");
            EXPECT_DOUBLE_EQ(e["ts"].get<double>(), 0.0015);
            EXPECT_DOUBLE_EQ(e["dur"].get<double>(), 1.9985);
        }
        if (e["ph"] == "C") {
            counter = true;
            EXPECT_DOUBLE_EQ(e["ts"].get<double>(), 0.000003);
            EXPECT_EQ(e["args"]["value"], 7);
        }
        if (e["ph"] == "M" && e["name"] == "thread_name") names = e["args"]["name"] == "track\\1";
    }
    EXPECT_TRUE(slice && counter && names);
}

// Events go to the file in batches written on another thread: across many batches, with
// tracks added between them and counters that repeat their value, every event is there once,
// in the order it was given.
TEST(Tracer, ManyBatchesKeepEveryEventInOrder) {
    const std::string dir = temp_dir("batches");
    constexpr int kEvents = 50000;
    {
        Tracer tracer({false, true, dir});
        int track = tracer.track("g", "t0");
        for (int i = 0; i < kEvents; ++i) {
            if (i % 10000 == 9999) track = tracer.track("g" + std::to_string(i), "t");
            tracer.slice(track, "s" + std::to_string(i), sc_core::sc_time(double(i), sc_core::SC_PS),
                         sc_core::sc_time(double(i + 1), sc_core::SC_PS));
            tracer.counter(track, "c", sc_core::sc_time(double(i), sc_core::SC_PS),
                           double(i / 2));  // every other repeats
        }
        tracer.finish();
    }
    std::ifstream in(dir + "/trace.perfetto.json");
    const auto json = nlohmann::json::parse(in);
    int slices = 0, counters = 0, tracks = 0;
    double last_counter = -1;
    for (const auto& e : json["traceEvents"]) {
        if (e["ph"] == "X") {
            ASSERT_EQ(e["name"], "s" + std::to_string(slices)) << "slice " << slices;
            ++slices;
        } else if (e["ph"] == "C") {
            ASSERT_GE(e["args"]["value"].get<double>(), last_counter);  // equal only at a new track
            last_counter = e["args"]["value"].get<double>();
            ++counters;
        } else if (e["name"] == "thread_name") {
            ++tracks;
        }
    }
    EXPECT_EQ(slices, kEvents);
    EXPECT_EQ(tracks, 1 + kEvents / 10000);
    // A new track starts its counter afresh: the value repeated across a track change is written again.
    EXPECT_EQ(counters, kEvents / 2 + kEvents / 10000);
}

// The VCD, written per change, is what SystemC's own writer (which samples every signal at
// every time step) writes for the same signals: a change at time 0, changes in one step on
// several signals, a value changed twice in one step (its last counts), a glitch undone within
// its step (not written), a signed word; only the header's date and version differ. (A run
// that pauses in its last step, as `surfvp run` does when the software is done, also has that
// step here; SystemC's writer never sampled it.)
TEST(Tracer, TheVcdIsWhatSystemCsSamplingWriterWrites) {
    const std::string dir = temp_dir("vcd_as_systemc");
    sc_core::sc_signal<bool> wire("wire");
    sc_core::sc_signal<uint32_t> word("word");
    sc_core::sc_signal<int> task("task");
    Tracer tracer({true, false, dir});
    sc_core::sc_trace_file* sampled = sc_core::sc_create_vcd_trace_file((dir + "/sampled").c_str());
    sampled->set_time_unit(1, sc_core::SC_PS);
    tracer.signal(wire, "b.wire");
    tracer.signal(word, "b.word");
    tracer.signal(task, "a.task");
    sc_core::sc_trace(sampled, wire, "b.wire");
    sc_core::sc_trace(sampled, word, "b.word");
    sc_core::sc_trace(sampled, task, "a.task");
    using sc_core::SC_NS;
    sc_core::sc_spawn([&] {
        task.write(-1);  // at time 0: an initial value
        sc_core::wait(10, SC_NS);
        wire.write(true), word.write(5);
        sc_core::wait(sc_core::SC_ZERO_TIME);
        word.write(6);  // the step's last value
        sc_core::wait(5, SC_NS);
        wire.write(false);
        sc_core::wait(sc_core::SC_ZERO_TIME);
        wire.write(true);  // undone within the step
        task.write(3);
        sc_core::wait(7, SC_NS);
        word.write(0), task.write(-2);
        sc_core::wait(3, SC_NS);
        wire.write(false);
    });
    sc_core::sc_start(40, SC_NS);
    tracer.finish();
    sc_core::sc_close_vcd_trace_file(sampled);
    const auto body = [](const std::string& vcd) { return vcd.substr(vcd.find("$timescale")); };
    const std::string ours = body(test::slurp(dir + "/trace.vcd")), theirs = body(test::slurp(dir + "/sampled.vcd"));
    EXPECT_NE(ours.find("\n#10000\n1aaaaa\nb110 aaaab\n\n#15000\nb11 aaaac\n"), std::string::npos) << ours;
    EXPECT_EQ(ours, theirs);
}

TEST(Tracer, UnfinishedTracesLeaveNoFiles) {
    const std::string dir = temp_dir("unfinished");
    {
        Tracer tracer({false, true, dir});
        tracer.slice(tracer.track("g", "t"), "x", sc_core::SC_ZERO_TIME, sc_core::sc_time(1, sc_core::SC_NS));
    }
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Tracer, OffMeansNoFilesAndNoTracks) {
    const std::string dir = temp_dir("off");
    Tracer tracer({false, false, dir});
    EXPECT_EQ(tracer.track("g", "t"), -1);
    EXPECT_TRUE(tracer.finish().empty());
    EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace surfvp
