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
//
// The timeline follows the trace-event format's conventions: every slice and counter has a
// category (its track's group: "plb2", "cpu", "frames"), slices carry their figures as
// arguments (bytes, master, address, frame) rather than in their names, slices on one track
// nest (a slice that would overlap another without nesting goes to a lane of its own, "write
// data (2)"), and flow events link an interrupt to the CPU's handling of it and on to the
// task it continues.
#include <cstdint>
#include <deque>
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

// A slice's arguments as the trace-event format's "args" object: numbers, text, addresses.
class TraceArgs {
public:
    TraceArgs& number(std::string_view key, double value);
    TraceArgs& text(std::string_view key, std::string_view value);
    TraceArgs& address(std::string_view key, uint64_t value);                 // "0x1f400000"
    std::string json() const { return json_.empty() ? json_ : json_ + "}"; }  // "" or {"k":v,...}

private:
    void key(std::string_view key);
    std::string json_;
};

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
        on_change(s.value_changed_event(), [this, index, bits_of] {
            write_timed(now_ps());
            vcd_->change(index, bits_of(), now_ps());
        });
    }
    // The save file's group titles, in display order ("iig" -> "SSA IIG").
    void group_titles(std::vector<std::pair<std::string, std::string>> titles) { titles_ = std::move(titles); }

    // VCD: a signal whose changes the model gives with their own times, which may be ahead
    // of the kernel's (the CPU runs ahead of it within its quantum): they are written among
    // the kernel-time signals' in time order. `value_names[v]` names value v in GTKWave (a
    // translate filter beside the save file). Returns the index for timed_change().
    int timed_signal(const std::string& name, unsigned bits, uint64_t initial,
                     std::vector<std::string> value_names = {});
    // From `ps` on (never before an earlier change of this signal).
    void timed_change(int index, uint64_t value, uint64_t ps);
    // GTKWave's named markers (A, B, ...: the first 26) at these times, e.g. frame starts.
    void marker(uint64_t ps, std::string label);

    // Perfetto: a named track in a named group (a "process" with a "thread" in the
    // trace-event format; the group is its events' category). Returns the track's id for
    // slice() and counter().
    int track(const std::string& group, const std::string& name);
    void slice(int track, std::string_view name, const sc_core::sc_time& start, const sc_core::sc_time& end,
               const TraceArgs& args = {});
    // A track made earlier, by its group and name; -1 when there is none.
    int track_of(const std::string& group, const std::string& name) const;
    // A flow arrow: `begin` at a slice on one track, `end` at a slice on another (bound to the
    // slice enclosing `at`). Ids are the caller's; flow_id() gives fresh ones.
    enum class Flow { begin, end };
    void flow(int track, const sc_core::sc_time& at, uint64_t id, Flow phase, std::string_view name);
    uint64_t flow_id() { return ++flows_; }
    // A flow handed from one model to another without either knowing the other (the INTC's
    // interrupt to the CPU that serves it): `post` leaves its id under `channel`, `take`
    // removes it (0: none).
    void post_flow(const std::string& channel, uint64_t id);
    uint64_t take_flow(const std::string& channel);
    // A counter holds its value until the next sample, so a sample that repeats it is not
    // written (the models sample their levels at every event, most of them unchanged).
    void counter(int track, std::string_view name, const sc_core::sc_time& at, double value);

    // Closes the files and gives them their final names, with the VCD's GTKWave save file
    // (trace.gtkw, and trace.tasks.txt it reads); returns the paths written.
    std::vector<std::string> finish();

private:
    // One lane of a track: its thread id and the slices written on it lately (start, end),
    // which a new slice must nest with.
    struct Lane {
        int tid;
        std::vector<std::pair<uint64_t, uint64_t>> recent;
    };
    struct Track {
        int pid;
        std::string name, group;
        std::vector<Lane> lanes;
        std::vector<std::pair<std::string, double>> counters;  // each counter's last value written
    };
    // A Perfetto event as recorded: its fields, its text in the batch's text: a metadata
    // event whole, or the name, then the category, then the arguments' JSON.
    struct Event {
        enum Kind : uint8_t { metadata, slice, counter, flow_begin, flow_end } kind;
        int pid, tid;
        uint64_t ps, duration_ps;  // slice: start and duration; counter, flow: its time; flow: id in value
        double value;
        uint32_t text, name_bytes, category_bytes, args_bytes;
    };
    struct TimedChange {
        uint64_t ps;
        int index;
        uint64_t value;
    };
    struct Batch {
        std::vector<Event> events;
        std::string text;
        bool first = false;  // holds the file's first event
    };
    void on_change(const sc_core::sc_event& changed, std::function<void()> note);  // a method process
    static uint64_t now_ps();
    void record(Event event, std::string_view name, std::string_view category = {}, std::string_view args = {});
    int lane_for(Track& track, uint64_t start, uint64_t end);  // the lane's tid
    void write_timed(uint64_t up_to_ps);                       // timed changes due by then
    void hand_over();                                          // the batch to the writing thread
    static void format(const Batch& batch, fmt::memory_buffer& out);
    void name_and_order(std::string_view what, int pid, int tid, std::string_view name, int sort_index);
    int group_id(const std::string& group);

    std::vector<std::string> write_gtkwave_save(const std::filesystem::path& dir);

    Options options_;
    std::unique_ptr<VcdWriter> vcd_;
    std::vector<VcdSignal> vcd_signals_;
    std::deque<TimedChange> timed_;  // not yet written, in time order
    uint64_t timed_end_ = 0;         // the latest timed change
    uint64_t written_up_to_ = 0;     // the kernel-time changes written so far reach this time
    std::vector<std::pair<uint64_t, std::string>> markers_;
    uint64_t flows_ = 0;
    int next_tid_ = 1;
    std::vector<std::pair<std::string, uint64_t>> posted_flows_;
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
