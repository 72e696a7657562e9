#pragma once
// What both IP blocks (SSA IIG, SSA FHG) count of their frames, and their names in the
// statistics: frames ended, ERRORs flagged, time busy and computing, and the utilisation.
#include <cstdint>
#include <functional>
#include <string>
#include <systemc>

#include "models/common/statistics.h"

namespace surfvp {

struct FrameStats {
    uint64_t frames = 0;
    sc_core::sc_time busy;       // from START to the frame's end, summed
    sc_core::sc_time computing;  // the block's core at work

    void ended(const sc_core::sc_time& began) {
        busy += sc_core::sc_time_stamp() - began;
        ++frames;
    }

    // frames, errors, busy_s, computing_s and utilisation under `s`; `busy_is` and
    // `computing_is` say what the block counts as each.
    void register_statistics(const Statistics::Scope& s, std::function<uint64_t()> errors, const std::string& busy_is,
                             const std::string& computing_is) const {
        s.count(
            "frames", [this] { return frames; }, "frames", "frames ended (done or failed)");
        s.count("errors", std::move(errors), "errors", "ERRORs flagged");
        s.time(
            "busy_s", [this] { return busy; }, busy_is);
        s.time(
            "computing_s", [this] { return computing; }, computing_is);
        s.share(
            "utilisation", [this] { return computing; }, "computing over the run");
    }
};

}  // namespace surfvp
