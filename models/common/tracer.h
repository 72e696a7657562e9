#pragma once
// The trace writers every model plugs into: a VCD (GTKWave, with a save file that opens it
// ready to read, gtkwave_save.h), written as each traced signal changes (vcd_writer.h: a
// method process per signal tells it), and a Chrome trace-event JSON timeline (Perfetto).
// Either can be off; a model asks `perfetto_on()` before
// building a slice's name, so tracing costs a branch when off. Files are written under
// temporary names and renamed by finish(), so an interrupted run leaves no half file
// under the final name. Perfetto's events are recorded as their fields, in batches, and a
// thread of their own (a Worker that does not spin: it gets a batch every few thousand
// events) formats and writes each batch, in order: the kernel's thread only records.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <fmt/format.h>
#include <functional>
#include <memory>
#include <systemc>
#include <type_traits>
#include <utility>
#include <vector>

#include "models/host/gtkwave_save.h"
#include "vcd_writer.h"
#include "models/host/worker.h"

namespace surfvp {

class Tracer {
public:
    struct Options {
        bool vcd = false;
        bool perfetto = false;
        std::string dir;  // output folder; files are DIR/trace.vcd and DIR/trace.perfetto.json
    };

    Tracer() = default;  // everything off
    explicit Tracer(const Options& options);
    ~Tracer();
    Tracer(const Tracer&) = delete;
    Tracer& operator=(const Tracer&) = delete;

    bool vcd_on() const { return vcd_ != nullptr; }
    bool perfetto_on() const { return perfetto_on_; }

    // VCD: trace a signal under a dotted name ("plb2.write_busy"); call before sc_start.
    template <typename T>
    void signal(const sc_core::sc_signal_in_if<T>& s, const std::string& name) {
        static_assert(std::is_integral_v<T>, "a traced signal is a wire or a word");
        if (!vcd_) return;
        const unsigned bits = std::is_same_v<T, bool> ? 1u : unsigned(8 * sizeof(T));
        // A word's bits as written: two's complement for a signed one.
        auto bits_of = [&s] {
            if constexpr (std::is_same_v<T, bool>)
                return uint64_t(s.read());
            else
                return uint64_t(std::make_unsigned_t<T>(s.read()));
        };
        const int index = vcd_->add(name, bits, bits_of());
        vcd_signals_.push_back({name, bits});
        on_change(s.value_changed_event(), [this, index, bits_of] { vcd_->change(index, bits_of(), now_ps()); });
    }
    // The save file's group titles, in display order ("iig" -> "SSA IIG").
    void group_titles(std::vector<std::pair<std::string, std::string>> titles) { titles_ = std::move(titles); }

    // Perfetto: a named track in a named group (a "process" with a "thread" in the
    // trace-event format). Returns the track's id for slice() and counter().
    int track(const std::string& group, const std::string& name);
    void slice(int track, std::string_view name, const sc_core::sc_time& start, const sc_core::sc_time& end);
    // A counter holds its value until the next sample, so a sample that repeats it is not
    // written (the models sample their levels at every event, most of them unchanged).
    void counter(int track, std::string_view name, const sc_core::sc_time& at, double value);

    // Closes the files and gives them their final names, with the VCD's GTKWave save file
    // (trace.gtkw, and trace.tasks.txt it reads); returns the paths written.
    std::vector<std::string> finish();

private:
    struct Track {
        int pid;
        int tid;
        std::vector<std::pair<std::string, double>> counters;  // each counter's last value written
    };
    // A Perfetto event as recorded: its fields, its text (a name, or a metadata event whole)
    // in the batch's text.
    struct Event {
        enum Kind : uint8_t { metadata, slice, counter } kind;
        int pid, tid;
        uint64_t ps, duration_ps;  // slice: start and duration; counter: its time
        double value;
        uint32_t text, text_bytes;
    };
    struct Batch {
        std::vector<Event> events;
        std::string text;
        bool first = false;  // holds the file's first event
    };
    void on_change(const sc_core::sc_event& changed, std::function<void()> note);  // a method process
    static uint64_t now_ps();
    void record(Event event, std::string_view text);
    void hand_over();  // the batch to the writing thread
    static void format(const Batch& batch, fmt::memory_buffer& out);
    void name_and_order(std::string_view what, int pid, int tid, std::string_view name, int sort_index);
    int group_id(const std::string& group);

    std::vector<std::string> write_gtkwave_save(const std::filesystem::path& dir);

    Options options_;
    std::unique_ptr<VcdWriter> vcd_;
    std::vector<VcdSignal> vcd_signals_;
    std::vector<std::pair<std::string, std::string>> titles_;
    bool perfetto_on_ = false;
    std::ofstream perfetto_;  // the writing thread's while it has batches
    Batch batch_;             // being recorded
    bool first_batch_ = true;
    std::vector<std::string> groups_;
    std::vector<Track> tracks_;
    bool finished_ = false;
    std::unique_ptr<Worker> writer_;  // last: stops (its batches written) before the stream goes
};

}  // namespace surfvp
