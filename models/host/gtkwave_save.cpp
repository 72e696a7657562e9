#include "gtkwave_save.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <map>

namespace surfvp {
namespace {

// The window gtkwave_save asks for, and what of it the waves get (the panes beside are
// 220 + 220 pixels plus borders): 860 pixels, a little less than they have.
constexpr int kWindowWidth = 1400, kWindowHeight = 800, kPaneWidth = 220, kWavePixels = 860;

// GTKWave trace flags (its analyzer.h): right-justified names, binary, decimal, a
// translated value, an analog step, a stretch row, group begin and end.
constexpr unsigned kRjustify = 0x20, kBinary = 0x8, kDecimal = 0x4, kTranslated = 0x2000, kAnalogStep = 0x8000,
                   kStretch = 0x20000, kBlank = 0x200, kGroupBegin = 0x800000, kGroupEnd = 0x1000000;

// The driver's value for "no task" on its marker signals (sw/libssa2: ~0u).
constexpr const char* kNoTask = "4294967295";

std::string group_of(const std::string& name) { return name.substr(0, name.find('.')); }

std::string trace_line(const VcdSignal& s, const GtkwaveSave& save, int& filters) {
    const std::string path = "SystemC." + s.name + (s.bits > 1 ? fmt::format("[{}:0]", s.bits - 1) : "");
    if (s.bits == 1) return fmt::format("@{:x}\n{}\n", kRjustify | kBinary, path);
    if (!s.value_names.empty()) {  // an enum: its names through a filter of its own, beside the tasks' (1)
        const std::string file =
            (std::filesystem::path(save.filter_path).parent_path() / gtkwave_value_filter_file(s)).string();
        return fmt::format("^{} {}\n@{:x}\n{}\n", ++filters, file, kRjustify | kDecimal | kTranslated, path);
    }
    const bool task = s.name.size() > 5 && s.name.compare(s.name.size() - 5, 5, "_task") == 0;
    if (task) return fmt::format("^1 {}\n@{:x}\n{}\n", save.filter_path, kRjustify | kDecimal | kTranslated, path);
    if (s.name.find("level") != std::string::npos)  // a FIFO level: a step curve four rows high
        return fmt::format("@{:x}\n{}\n@{:x}\n-\n-\n-\n", kRjustify | kDecimal | kAnalogStep, path, kStretch);
    return fmt::format("@{:x}\n{}\n", kRjustify | kDecimal, path);
}

}  // namespace

double gtkwave_zoom(uint64_t end_ps) { return -std::log2(200.0 * double(std::max<uint64_t>(end_ps, 1)) / kWavePixels); }

std::string gtkwave_task_filter() { return fmt::format("{} none\n", kNoTask); }

std::string gtkwave_value_filter(const VcdSignal& signal) {
    std::string text;
    for (size_t v = 0; v < signal.value_names.size(); ++v) text += fmt::format("{} {}\n", v, signal.value_names[v]);
    return text;
}

std::string gtkwave_value_filter_file(const VcdSignal& signal) { return "trace." + signal.name + ".txt"; }

std::string gtkwave_save(const std::vector<VcdSignal>& signals, const GtkwaveSave& save) {
    std::vector<std::string> order;
    std::map<std::string, std::string> title;
    for (const auto& [group, text] : save.titles) order.push_back(group), title[group] = text;
    for (const VcdSignal& s : signals)
        if (std::find(order.begin(), order.end(), group_of(s.name)) == order.end()) order.push_back(group_of(s.name));
    std::string out = fmt::format(
        "[*] surfvp: open with `gtkwave {}`\n[dumpfile] \"{}\"\n[savefile] \"{}\"\n[timestart] 0\n[size] {} {}\n"
        "[pos] 0 0\n*{:.6f} -1",
        save.save_path, save.vcd_path, save.save_path, kWindowWidth, kWindowHeight, gtkwave_zoom(save.end_ps));
    for (size_t i = 0; i < 26; ++i)  // the named markers A to Z
        out += i < save.markers.size() ? fmt::format(" {}", save.markers[i]) : std::string(" -1");
    out += fmt::format("\n[sst_width] {0}\n[signals_width] {0}\n[sst_expanded] 1\n", kPaneWidth);
    int filters = 1;  // 1: the tasks' filter
    for (const std::string& group : order) {
        std::string traces;
        for (const VcdSignal& s : signals)
            if (group_of(s.name) == group) traces += trace_line(s, save, filters);
        if (traces.empty()) continue;
        const std::string name = title.count(group) ? title[group] : group;
        out += fmt::format("@{:x}\n-{}\n{}@{:x}\n-{}\n", kGroupBegin | kBlank, name, traces, kGroupEnd | kBlank, name);
    }
    return out;
}

}  // namespace surfvp
