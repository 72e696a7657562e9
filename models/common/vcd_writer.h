#pragma once
// A VCD file written as the signals change (Tracer's, for GTKWave). SystemC's own writer
// compares every traced signal with its last value at every simulated time step, which cost
// more than the rest of the VCD (a budget run writes changes at some 55 thousand steps of many
// more); this one is told of each change and writes, per time step, the signals whose value at
// its end differs from the last one written, in the order they were added: what a per-step
// sampler writes (no deltas). The layout is SystemC's (a top scope "SystemC", one scope per
// dotted prefix in name order, identifiers "aaaaa", "aaaab", ...), so GTKWave save files and
// readers see the same file. Plain C++: the caller says the time of each change.
#include <cstdint>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <vector>

namespace surfvp {

class VcdWriter {
public:
    // Opens `path` for writing; throws EnvironmentError when it cannot.
    explicit VcdWriter(const std::string& path);

    // A signal under a dotted name ("plb2.write_busy") of `bits` bits (1: a wire of 0 and 1)
    // with its value before the simulation; returns its index for change(). Before any change.
    int add(const std::string& name, unsigned bits, uint64_t initial);
    // Signal `index` holds `value` from `time_ps` on; times never decrease.
    void change(int index, uint64_t value, uint64_t time_ps);
    // Writes what is pending and the end time, and closes the file; false when a write failed
    // (a full disk).
    bool close(uint64_t end_ps);

private:
    struct Signal {
        std::string name;
        unsigned bits;
        std::string id;
        uint64_t value, written;  // at the latest time; as last written
        bool pending = false;     // changed at the pending time
    };
    void header();
    void flush();  // the pending time step
    void put_value(const Signal& s);
    void stamp(uint64_t ps);  // a time step's "#<ps>" line
    void drain();             // the buffer to the file

    std::ofstream out_;
    fmt::memory_buffer buffer_;
    std::vector<Signal> signals_;
    std::vector<int> pending_;  // signals changed at pending_ps_
    uint64_t pending_ps_ = 0;
    uint64_t stamped_ps_ = 0;  // the last "#<ps>" written
    bool started_ = false;     // header and initial values written
};

}  // namespace surfvp
