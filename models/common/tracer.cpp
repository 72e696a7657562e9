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

// Slices a lane keeps to check a new one against: the latest few hundred (a slice that
// would overlap an older one is older than any the models keep open).
constexpr size_t kLaneMemory = 256;

}  // namespace

void TraceArgs::key(std::string_view key) {
    json_ += json_.empty() ? "{" : ",";
    fmt::memory_buffer out;
    put_json_string(out, key);
    json_.append(out.data(), out.size());
    json_ += ':';
}

TraceArgs& TraceArgs::number(std::string_view k, double value) {
    key(k);
    json_ += fmt::format("{}", value);
    return *this;
}

TraceArgs& TraceArgs::text(std::string_view k, std::string_view value) {
    key(k);
    fmt::memory_buffer out;
    put_json_string(out, value);
    json_.append(out.data(), out.size());
    return *this;
}

TraceArgs& TraceArgs::address(std::string_view k, uint64_t value) {
    key(k);
    json_ += fmt::format("\"0x{:x}\"", value);
    return *this;
}

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

void Tracer::record(Event event, std::string_view name, std::string_view category, std::string_view args) {
    event.text = uint32_t(batch_.text.size());
    event.name_bytes = uint32_t(name.size());
    event.category_bytes = uint32_t(category.size());
    event.args_bytes = uint32_t(args.size());
    batch_.text.append(name);
    batch_.text.append(category);
    batch_.text.append(args);
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
        const char* text = batch.text.data() + e.text;
        const std::string_view name(text, e.name_bytes), category(text + e.name_bytes, e.category_bytes),
            args(text + e.name_bytes + e.category_bytes, e.args_bytes);
        if (e.kind == Event::metadata) {
            put(out, name);
            continue;
        }
        static constexpr const char* phase[] = {"", "X", "C", "s", "f"};
        fmt::format_to(std::back_inserter(out), FMT_COMPILE(R"({{"ph":"{}","name":)"), phase[e.kind]);
        put_json_string(out, name);
        put(out, R"(,"cat":)");
        put_json_string(out, category);
        fmt::format_to(std::back_inserter(out), FMT_COMPILE(R"(,"pid":{},"tid":{},"ts":)"), e.pid, e.tid);
        put_micros(out, e.ps);
        switch (e.kind) {
            case Event::slice:
                put(out, R"(,"dur":)");
                put_micros(out, e.duration_ps);
                if (!args.empty()) put(out, R"(,"args":)"), put(out, args);
                break;
            case Event::counter:
                fmt::format_to(std::back_inserter(out), FMT_COMPILE(R"(,"args":{{"value":{}}})"), e.value);
                break;
            case Event::flow_begin:
            case Event::flow_end:  // bound to the slice enclosing its time
                fmt::format_to(std::back_inserter(out), FMT_COMPILE(R"(,"id":{},"bp":"e")"), uint64_t(e.value));
                break;
            default:
                break;
        }
        put(out, "}");
    }
}

// A process's or thread's name and its place in the timeline's order, as two metadata events.
void Tracer::name_and_order(std::string_view what, int pid, int tid, std::string_view name, int sort_index) {
    fmt::memory_buffer text;
    fmt::format_to(std::back_inserter(text), R"({{"ph":"M","name":"{}_name","pid":{},"tid":{},"args":{{"name":)", what,
                   pid, tid);
    put_json_string(text, name);
    put(text, "}}");
    record({Event::metadata, pid, tid, 0, 0, 0, 0, 0, 0, 0}, {text.data(), text.size()});
    text.clear();
    fmt::format_to(std::back_inserter(text),
                   R"({{"ph":"M","name":"{}_sort_index","pid":{},"tid":{},"args":{{"sort_index":{}}}}})", what, pid,
                   tid, sort_index);
    record({Event::metadata, pid, tid, 0, 0, 0, 0, 0, 0, 0}, {text.data(), text.size()});
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
    const int tid = next_tid_++;
    tracks_.push_back({pid, name, group, {{tid, {}}}, {}});
    name_and_order("thread", pid, tid, name, tid * 16);
    return static_cast<int>(tracks_.size()) - 1;
}

// Slices are written as they end, so a new one [start, end] comes after every slice of its
// lane that ends before it. It nests with one (s, e) unless s < start < e < end: then it
// goes to the next lane, made when none takes it ("write data (2)", ordered after its track).
int Tracer::lane_for(Track& track, uint64_t start, uint64_t end) {
    for (Lane& lane : track.lanes) {
        const bool crosses = std::any_of(lane.recent.begin(), lane.recent.end(), [&](const auto& s) {
            return s.first < start && start < s.second && s.second < end;
        });
        if (crosses) continue;
        if (lane.recent.size() == kLaneMemory) lane.recent.erase(lane.recent.begin());
        lane.recent.emplace_back(start, end);
        return lane.tid;
    }
    const int tid = next_tid_++;
    const int first = track.lanes.front().tid;
    track.lanes.push_back({tid, {{start, end}}});
    name_and_order("thread", track.pid, tid, fmt::format("{} ({})", track.name, track.lanes.size()),
                   first * 16 + int(track.lanes.size()));
    return tid;
}

void Tracer::slice(int track, std::string_view name, const sc_core::sc_time& start, const sc_core::sc_time& end,
                   const TraceArgs& args) {
    if (!perfetto_on() || track < 0) return;
    Track& t = tracks_[track];
    const int tid = lane_for(t, start.value(), end.value());
    record({Event::slice, t.pid, tid, start.value(), end.value() - start.value(), 0, 0, 0, 0, 0}, name, t.group,
           args.json());
}

int Tracer::track_of(const std::string& group, const std::string& name) const {
    for (size_t i = 0; i < tracks_.size(); ++i)
        if (tracks_[i].group == group && tracks_[i].name == name) return int(i);
    return -1;
}

void Tracer::flow(int track, const sc_core::sc_time& at, uint64_t id, Flow phase, std::string_view name) {
    if (!perfetto_on() || track < 0) return;
    const Track& t = tracks_[track];
    record({phase == Flow::begin ? Event::flow_begin : Event::flow_end, t.pid, t.lanes.front().tid, at.value(), 0,
            double(id), 0, 0, 0, 0},
           name, "flow");
}

void Tracer::post_flow(const std::string& channel, uint64_t id) {
    if (!perfetto_on()) return;
    posted_flows_.emplace_back(channel, id);
}

uint64_t Tracer::take_flow(const std::string& channel) {
    for (auto it = posted_flows_.begin(); it != posted_flows_.end(); ++it)
        if (it->first == channel) {
            const uint64_t id = it->second;
            posted_flows_.erase(it);
            return id;
        }
    return 0;
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
    record({Event::counter, tracks_[track].pid, 0, at.value(), 0, value, 0, 0, 0, 0}, name, tracks_[track].group);
}

int Tracer::timed_signal(const std::string& name, unsigned bits, uint64_t initial,
                         std::vector<std::string> value_names) {
    if (!vcd_) return -1;
    const int index = vcd_->add(name, bits, initial);
    vcd_signals_.push_back({name, bits, std::move(value_names)});
    return index;
}

void Tracer::timed_change(int index, uint64_t value, uint64_t ps) {
    if (!vcd_ || index < 0) return;
    // A model may learn of a change only after the kernel's time has passed it (the CPU's
    // phases within a compute() that waited for its fills): it is written at the latest time
    // already written, so that the file's times never go back.
    ps = std::max(ps, written_up_to_);
    if (!timed_.empty()) ps = std::max(ps, timed_.back().ps);
    timed_.push_back({ps, index, value});
    timed_end_ = std::max(timed_end_, ps);
}

// The timed changes due by `up_to_ps`, before a kernel-time change at that time is written.
void Tracer::write_timed(uint64_t up_to_ps) {
    written_up_to_ = std::max(written_up_to_, up_to_ps);
    while (!timed_.empty() && timed_.front().ps <= up_to_ps) {
        vcd_->change(timed_.front().index, timed_.front().value, timed_.front().ps);
        timed_.pop_front();
    }
}

void Tracer::marker(uint64_t ps, std::string label) { markers_.emplace_back(ps, std::move(label)); }

std::vector<std::string> Tracer::write_gtkwave_save(const fs::path& dir) {
    const fs::path absolute = fs::absolute(dir);
    std::sort(markers_.begin(), markers_.end());
    std::vector<uint64_t> markers;
    for (const auto& m : markers_) markers.push_back(m.first);
    GtkwaveSave save{(absolute / "trace.vcd").string(),
                     (absolute / "trace.gtkw").string(),
                     (absolute / "trace.tasks.txt").string(),
                     sc_core::sc_time_stamp().value(),
                     titles_,
                     markers};
    std::vector<std::pair<std::string, std::string>> files = {{"trace.gtkw", gtkwave_save(vcd_signals_, save)},
                                                              {"trace.tasks.txt", gtkwave_task_filter()}};
    for (const VcdSignal& s : vcd_signals_)
        if (!s.value_names.empty()) files.emplace_back(gtkwave_value_filter_file(s), gtkwave_value_filter(s));
    std::vector<std::string> written;
    for (const auto& [name, text] : files) {
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
        write_timed(UINT64_MAX);
        const bool whole = vcd_->close(std::max(now_ps(), timed_end_));
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
