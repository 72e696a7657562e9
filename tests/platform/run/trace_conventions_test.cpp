// The traces follow their formats' conventions (traces/README.md). Perfetto: slices on one
// track nest, every event has a category, slices carry their figures as arguments, and flows
// link each interrupt to the CPU's handling and the FHG's to the descriptors it starts. VCD:
// the CPU's phase as a named enum signal and GTKWave markers at the frames' starts.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "cli.h"
#include "vcd_reader.h"

namespace surfvp::test {
namespace {
using Json = nlohmann::json;

// The budget scenario, 4 frames of 512x384 with both traces.
const std::string& traced_run() {
    static const std::string out = [] {
        const std::string dir = fresh_dir("trace_conventions");
        const auto r = surfvp("run " + kBudget + kOneRun +
                              " --quiet --set surf.frames=4 --set surf.width=512 --set surf.height=384 --out " + dir);
        EXPECT_LE(r.exit_code, 1) << r.err;
        return dir;
    }();
    return out;
}

uint64_t ps(const Json& micros) { return uint64_t(std::llround(micros.get<double>() * 1e6)); }

struct Slice {
    uint64_t start, end;
};

TEST(TraceConventions, PerfettoSlicesNestAndCarryCategoriesArgumentsAndFlows) {
    const Json trace = Json::parse(slurp(traced_run() + "/trace.perfetto.json"));
    std::map<std::pair<int, int>, std::vector<Slice>> tracks;
    std::map<uint64_t, std::pair<const Json*, const Json*>> flows;  // id -> begin, end
    size_t slices = 0, with_args = 0, plb_without_bytes = 0;
    for (const Json& e : trace["traceEvents"]) {
        const std::string ph = e["ph"];
        if (ph == "M") continue;
        EXPECT_TRUE(e.contains("cat") && !e["cat"].get<std::string>().empty()) << e;
        if (ph == "X") {
            ++slices;
            tracks[{e["pid"], e["tid"]}].push_back({ps(e["ts"]), ps(e["ts"]) + ps(e["dur"])});
            with_args += e.contains("args");
            const std::string cat = e["cat"];
            if ((cat == "plb1" || cat == "plb2") && !(e.contains("args") && e["args"].contains("bytes")))
                ++plb_without_bytes;
        }
        if (ph == "s") flows[e["id"]].first = &e;
        if (ph == "f") flows[e["id"]].second = &e;
    }
    // Nesting: sorted by start (longest first), a slice ends within the one it starts in.
    size_t overlaps = 0;
    for (auto& [track, list] : tracks) {
        std::sort(list.begin(), list.end(), [](const Slice& a, const Slice& b) {
            return a.start != b.start ? a.start < b.start : a.end > b.end;
        });
        std::vector<uint64_t> open;  // the ends of the slices enclosing the current one
        for (const Slice& s : list) {
            while (!open.empty() && open.back() <= s.start) open.pop_back();
            overlaps += !open.empty() && s.end > open.back();
            open.push_back(s.end);
        }
    }
    EXPECT_GT(slices, 10000u);
    EXPECT_EQ(overlaps, 0u);
    EXPECT_EQ(plb_without_bytes, 0u);
    EXPECT_GT(with_args, slices / 2);
    // Flows: each begun and ended, each end inside a slice of its track.
    const Json report = Json::parse(slurp(traced_run() + "/report.json"));
    const size_t interrupts = report["interrupts"]["raised"].get<size_t>();
    size_t interrupt_flows = 0, frame_flows = 0;
    for (const auto& [id, ends] : flows) {
        ASSERT_TRUE(ends.first && ends.second) << "flow " << id;
        const Json& end = *ends.second;
        const auto& list = tracks[{end["pid"], end["tid"]}];
        const uint64_t at = ps(end["ts"]);
        EXPECT_TRUE(std::any_of(list.begin(), list.end(), [&](const Slice& s) { return s.start <= at && at < s.end; }))
            << end;
        interrupt_flows += end["name"] == "interrupt";
        frame_flows += end["name"] == "continues the frame";
    }
    EXPECT_EQ(interrupt_flows, interrupts);
    EXPECT_EQ(frame_flows, 4u);
}

TEST(TraceConventions, TheVcdHasTheCpuPhaseAsANamedEnumAndMarkersAtFrameStarts) {
    // The file's times never go back (GTKWave refuses "time backtracking"), also where the
    // CPU's phase is given at its own time, ahead of the kernel's.
    std::istringstream text(slurp(traced_run() + "/trace.vcd"));
    uint64_t previous = 0;
    size_t backwards = 0;
    for (std::string line; std::getline(text, line);)
        if (line.size() > 1 && line[0] == '#') {
            const uint64_t t = std::stoull(line.substr(1));
            backwards += t < previous;
            previous = t;
        }
    EXPECT_EQ(backwards, 0u);
    const Vcd vcd = Vcd::read(traced_run() + "/trace.vcd");
    ASSERT_TRUE(vcd.changes.count("cpu.phase"));
    std::set<std::string> values;
    uint64_t last = 0;
    for (const auto& [t, v] : vcd.changes.at("cpu.phase")) {
        values.insert(v);
        EXPECT_GE(t, last);
        last = t;
    }
    // idle, waiting, driver and the software steps (check, interpolation, ... descriptor) all appear.
    EXPECT_GE(values.size(), 7u) << values.size();
    const std::string names = slurp(traced_run() + "/trace.cpu.phase.txt");
    for (const char* n :
         {"0 idle", "1 waiting_irq", "2 driver", "3 check", "4 interpolation", "6 orientation", "7 descriptor"})
        EXPECT_NE(names.find(n), std::string::npos) << n;
    const std::string gtkw = slurp(traced_run() + "/trace.gtkw");
    EXPECT_NE(gtkw.find("trace.cpu.phase.txt\n"), std::string::npos);
    // The markers line: zoom, the primary marker, then A, B, C, D at the 4 frames' starts.
    const size_t star = gtkw.find("\n*");
    ASSERT_NE(star, std::string::npos);
    std::istringstream line(gtkw.substr(star + 2, gtkw.find('\n', star + 2) - star - 2));
    double zoom = 0;
    long long primary = 0;
    line >> zoom >> primary;
    std::vector<long long> markers;
    for (long long m; line >> m;)
        if (m >= 0) markers.push_back(m);
    const Json report = Json::parse(slurp(traced_run() + "/report.json"));
    ASSERT_EQ(markers.size(), 4u);
    EXPECT_TRUE(std::is_sorted(markers.begin(), markers.end()));
    EXPECT_GT(markers[1], markers[0]);
}

}  // namespace
}  // namespace surfvp::test
