#include "tracer.h"

#include "models/host/atomic_file.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fmt/compile.h>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <memory>
#include <unistd.h>
#include <utility>

namespace surfvp {
namespace fs = std::filesystem;
namespace {

// Temporary names of this process's traces (two runs on one folder never share one).
std::string vcd_temp() { return fmt::format("trace.vcd.{}.partial", ::getpid()); }
std::string perfetto_temp() { return fmt::format("trace.perfetto.json.{}.partial", ::getpid()); }

// Events a batch holds before it goes to the writing thread (~0.5 MB of text).
constexpr size_t kBatchEvents = 1 << 13;

// Trace-event timestamps are microseconds; the simulator resolves picoseconds.
void put_micros(fmt::memory_buffer& out, uint64_t ps) {
    fmt::format_to(std::back_inserter(out), FMT_COMPILE("{}.{:06}"), ps / 1000000, ps % 1000000);
}

// Event names are short and mostly plain: escaped here rather than through a JSON value.
void put_json_string(fmt::memory_buffer& out, std::string_view text) {
    out.push_back('"');
    for (char c : text) {
        if (c == '"' || c == '\\') out.push_back('\\');
        if (static_cast<unsigned char>(c) < 0x20)
            fmt::format_to(std::back_inserter(out), "\\u{:04x}", unsigned(c));
        else
            out.push_back(c);
    }
    out.push_back('"');
}

void put(fmt::memory_buffer& out, std::string_view text) { out.append(text.data(), text.data() + text.size()); }

}  // namespace

Tracer::Tracer(const Options& options) : options_(options) {
    if (options.vcd) vcd_ = std::make_unique<VcdWriter>((fs::path(options.dir) / vcd_temp()).string());
    if (options.perfetto) {
        perfetto_.open(fs::path(options.dir) / perfetto_temp(), std::ios::binary | std::ios::trunc);
        if (!perfetto_) throw EnvironmentError("cannot write " + (fs::path(options.dir) / perfetto_temp()).string());
        perfetto_ << "{\"displayTimeUnit\":\"ns\",\"traceEvents\":[";
        perfetto_on_ = true;
        writer_ = std::make_unique<Worker>(std::chrono::microseconds(0));
    }
}

Tracer::~Tracer() {
    if (finished_) return;
    writer_.reset();  // its batches written: the stream is this thread's again
    // A run that did not finish removes its partial files rather than leave them behind.
    vcd_.reset();
    if (perfetto_.is_open()) perfetto_.close();
    std::error_code ignored;
    fs::remove(fs::path(options_.dir) / vcd_temp(), ignored);
    fs::remove(fs::path(options_.dir) / perfetto_temp(), ignored);
}

// Runs `note` in the delta cycle after each notification of `changed` (a signal's value change),
// never at the start.
void Tracer::on_change(const sc_core::sc_event& changed, std::function<void()> note) {
    sc_core::sc_spawn_options options;
    options.spawn_method();
    options.dont_initialize();
    options.set_sensitivity(&changed);
    sc_core::sc_spawn(std::move(note), sc_core::sc_gen_unique_name("vcd_note"), &options);
}

// The simulator resolves picoseconds (VCD and Perfetto times are its values).
uint64_t Tracer::now_ps() { return sc_core::sc_time_stamp().value(); }

void Tracer::record(Event event, std::string_view text) {
    event.text = uint32_t(batch_.text.size());
    event.text_bytes = uint32_t(text.size());
    batch_.text.append(text);
    batch_.events.push_back(event);
    if (batch_.events.size() == kBatchEvents) hand_over();
}

// Batches are formatted and written on the writer's thread, one after the other in the order
// handed over (nobody waits on the worker, so no other thread runs one).
void Tracer::hand_over() {
    if (batch_.events.empty()) return;
    batch_.first = std::exchange(first_batch_, false);
    writer_->submit([this, batch = std::make_shared<Batch>(std::move(batch_))] {
        fmt::memory_buffer out;
        format(*batch, out);
        perfetto_.write(out.data(),
                        std::streamsize(out.size()));  // a failed stream (a full disk) only stops taking data
    });
    batch_ = Batch();
    batch_.events.reserve(kBatchEvents);
}

void Tracer::format(const Batch& batch, fmt::memory_buffer& out) {
    bool first = batch.first;
    for (const Event& e : batch.events) {
        put(out, std::exchange(first, false) ? "\n" : ",\n");
        const std::string_view text(batch.text.data() + e.text, e.text_bytes);
        switch (e.kind) {
            case Event::metadata:
                put(out, text);
                break;
            case Event::slice:
                put(out, R"({"ph":"X","name":)");
                put_json_string(out, text);
                fmt::format_to(std::back_inserter(out), FMT_COMPILE(R"(,"pid":{},"tid":{},"ts":)"), e.pid, e.tid);
                put_micros(out, e.ps);
                put(out, R"(,"dur":)");
                put_micros(out, e.duration_ps);
                put(out, "}");
                break;
            case Event::counter:
                put(out, R"({"ph":"C","name":)");
                put_json_string(out, text);
                fmt::format_to(std::back_inserter(out), FMT_COMPILE(R"(,"pid":{},"ts":)"), e.pid);
                put_micros(out, e.ps);
                fmt::format_to(std::back_inserter(out), FMT_COMPILE(R"(,"args":{{"value":{}}}}})"), e.value);
                break;
        }
    }
}

// A process's or thread's name and its place in the timeline's order, as two metadata events.
void Tracer::name_and_order(std::string_view what, int pid, int tid, std::string_view name, int sort_index) {
    fmt::memory_buffer text;
    fmt::format_to(std::back_inserter(text), R"({{"ph":"M","name":"{}_name","pid":{},"tid":{},"args":{{"name":)", what,
                   pid, tid);
    put_json_string(text, name);
    put(text, "}}");
    record({Event::metadata, pid, tid, 0, 0, 0, 0, 0}, {text.data(), text.size()});
    text.clear();
    fmt::format_to(std::back_inserter(text),
                   R"({{"ph":"M","name":"{}_sort_index","pid":{},"tid":{},"args":{{"sort_index":{}}}}})", what, pid,
                   tid, sort_index);
    record({Event::metadata, pid, tid, 0, 0, 0, 0, 0}, {text.data(), text.size()});
}

int Tracer::group_id(const std::string& group) {
    for (size_t i = 0; i < groups_.size(); ++i)
        if (groups_[i] == group) return static_cast<int>(i) + 1;
    groups_.push_back(group);
    const int pid = static_cast<int>(groups_.size());
    name_and_order("process", pid, 0, group, pid);
    return pid;
}

int Tracer::track(const std::string& group, const std::string& name) {
    if (!perfetto_on()) return -1;
    const int pid = group_id(group);
    const int tid = static_cast<int>(tracks_.size()) + 1;
    tracks_.push_back({pid, tid, {}});
    name_and_order("thread", pid, tid, name, tid);
    return static_cast<int>(tracks_.size()) - 1;
}

void Tracer::slice(int track, std::string_view name, const sc_core::sc_time& start, const sc_core::sc_time& end) {
    if (!perfetto_on() || track < 0) return;
    const Track& t = tracks_[track];
    record({Event::slice, t.pid, t.tid, start.value(), end.value() - start.value(), 0, 0, 0}, name);
}

void Tracer::counter(int track, std::string_view name, const sc_core::sc_time& at, double value) {
    if (!perfetto_on() || track < 0) return;
    auto& counters = tracks_[track].counters;
    auto last = std::find_if(counters.begin(), counters.end(), [&](const auto& c) { return c.first == name; });
    if (last == counters.end())
        counters.emplace_back(std::string(name), value);
    else if (last->second == value)
        return;
    else
        last->second = value;
    record({Event::counter, tracks_[track].pid, 0, at.value(), 0, value, 0, 0}, name);
}

std::vector<std::string> Tracer::write_gtkwave_save(const fs::path& dir) {
    const fs::path absolute = fs::absolute(dir);
    GtkwaveSave save{(absolute / "trace.vcd").string(), (absolute / "trace.gtkw").string(),
                     (absolute / "trace.tasks.txt").string(), sc_core::sc_time_stamp().value(), titles_};
    std::vector<std::string> written;
    for (const auto& [name, text] : {std::pair{std::string("trace.gtkw"), gtkwave_save(vcd_signals_, save)},
                                     std::pair{std::string("trace.tasks.txt"), gtkwave_task_filter()}}) {
        write_file_atomically(dir / name, text);
        written.push_back((dir / name).string());
    }
    return written;
}

namespace {

// A trace written under its temporary name gets its final one, or, cut short, is removed.
// Returns the final path.
std::string settle(const fs::path& dir, const std::string& temp, const std::string& name, bool whole) {
    if (!whole) {
        std::error_code ignored;
        fs::remove(dir / temp, ignored);
        throw EnvironmentError((dir / name).string() + ": the write failed, the file was cut short (disk full?)");
    }
    fs::rename(dir / temp, dir / name);
    return (dir / name).string();
}

}  // namespace

std::vector<std::string> Tracer::finish() {
    std::vector<std::string> written;
    const fs::path dir(options_.dir);
    if (vcd_) {
        const bool whole = vcd_->close(now_ps());
        vcd_.reset();
        written.push_back(settle(dir, vcd_temp(), "trace.vcd", whole));
        for (const std::string& f : write_gtkwave_save(dir)) written.push_back(f);
    }
    if (perfetto_on_) {
        hand_over();
        writer_.reset();  // every batch written
        perfetto_on_ = false;
        perfetto_ << "\n]}\n";
        perfetto_.close();
        written.push_back(settle(dir, perfetto_temp(), "trace.perfetto.json", bool(perfetto_)));
    }
    finished_ = true;
    return written;
}

}  // namespace surfvp
