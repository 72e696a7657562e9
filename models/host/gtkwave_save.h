#pragma once
// A GTKWave save file for one run's VCD, so that `gtkwave trace.gtkw` opens ready to read:
// the signals grouped by block, zoomed to the whole run, FIFO levels drawn as analog steps,
// task numbers with "none" for the driver's no-task value. Plain C++.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace surfvp {

struct VcdSignal {
    std::string name;                           // dotted, as traced ("fhg.maxima_fifo_level")
    unsigned bits;                              // 1 for a bool
    std::vector<std::string> value_names = {};  // value v's name (an enum: "cpu.phase"), or none
};

struct GtkwaveSave {
    std::string vcd_path, save_path, filter_path;  // absolute: GTKWave finds a moved folder from them
    uint64_t end_ps = 0;                           // the run's simulated time
    // Group titles in display order ("iig" -> "SSA IIG"); other groups follow as traced.
    std::vector<std::pair<std::string, std::string>> titles;
    std::vector<uint64_t> markers;  // GTKWave's named markers A, B, ... (at most 26) at these times
};

// An enum signal's translate filter (each value's name), and the file it goes in beside the
// save file (trace.<signal>.txt).
std::string gtkwave_value_filter(const VcdSignal& signal);
std::string gtkwave_value_filter_file(const VcdSignal& signal);

// The save file's text; `filter_text()` is the value-to-name file it refers to.
std::string gtkwave_save(const std::vector<VcdSignal>& signals, const GtkwaveSave& save);
std::string gtkwave_task_filter();

// GTKWave's zoom for `end_ps` across the wave pane of gtkwave_save's window (measured: a
// pixel covers 2^-zoom / 200 time units).
double gtkwave_zoom(uint64_t end_ps);

}  // namespace surfvp
