// The trace writers: files appear under their final names only when finished, and the
// timeline is valid JSON whatever the names hold.
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>

#include "models/common/tracer.h"

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
