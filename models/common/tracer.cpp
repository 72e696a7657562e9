#include "tracer.h"

#include "atomic_file.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fmt/compile.h>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <unistd.h>

namespace surfvp {
namespace fs = std::filesystem;
namespace {

// Temporary names of this process's traces (two runs on one folder never share one);
// SystemC appends ".vcd" to the name it is given.
std::string vcd_temp() { return fmt::format("trace.vcd.{}.partial", ::getpid()); }
std::string perfetto_temp() { return fmt::format("trace.perfetto.json.{}.partial", ::getpid()); }

// Perfetto's events are formatted into a buffer (no string per event: the timeline writer is
// on every transaction's path when tracing is on) and written to the file in large pieces.
constexpr size_t kFlushBytes = 1 << 20;

// Trace-event timestamps are microseconds; the simulator resolves picoseconds.
void put_micros(fmt::memory_buffer& out, const sc_core::sc_time& t) {
    const auto ps = t.value();
    fmt::format_to(std::back_inserter(out), FMT_COMPILE("{}.{:06}"), ps / 1000000, ps % 1000000);
}

// Event names are short and mostly plain: escaped here rather than through a JSON value.
void put_json_string(fmt::memory_buffer& out, std::string_view text) {
    out.push_back('"');
    for (char c : text) {
        if (c == '"' || c == '\\') out.push_back('\\');
        if (static_cast<unsigned char>(c) < 0x20) fmt::format_to(std::back_inserter(out), "\\u{:04x}", unsigned(c));
        else out.push_back(c);
    }
    out.push_back('"');
}

void put(fmt::memory_buffer& out, std::string_view text) { out.append(text.data(), text.data() + text.size()); }

// SystemC's VCD writer does not report failed writes; a complete file ends with the run's
// end time ("#<ps>"), which a file cut short by a full disk lacks.
void check_vcd_complete(const fs::path& vcd) {
    const std::string end = fmt::format("#{}\n", sc_core::sc_time_stamp().value());
    std::ifstream in(vcd, std::ios::binary | std::ios::ate);
    const std::streamoff size = in ? std::streamoff(in.tellg()) : 0;
    std::string tail(std::min<std::streamoff>(size, std::streamoff(end.size())), '\0');
    if (in && size >= std::streamoff(end.size())) {
        in.seekg(size - std::streamoff(end.size()));
        in.read(tail.data(), std::streamsize(tail.size()));
    }
    if (tail == end) return;
    std::error_code ignored;
    fs::remove(vcd, ignored);
    throw EnvironmentError(vcd.parent_path().string() + "/trace.vcd: the write failed, the file was cut short (disk full?)");
}

}  // namespace

Tracer::Tracer(const Options& options) : options_(options) {
    if (options.vcd) {
        vcd_ = sc_core::sc_create_vcd_trace_file((fs::path(options.dir) / vcd_temp()).string().c_str());
        vcd_->set_time_unit(1, sc_core::SC_PS);
    }
    if (options.perfetto) {
        perfetto_.open(fs::path(options.dir) / perfetto_temp(), std::ios::binary | std::ios::trunc);
        if (!perfetto_) throw EnvironmentError("cannot write " + (fs::path(options.dir) / perfetto_temp()).string());
        perfetto_ << "{\"displayTimeUnit\":\"ns\",\"traceEvents\":[";
    }
}

Tracer::~Tracer() {
    if (finished_) return;
    // A run that did not finish removes its partial files rather than leave them behind.
    if (vcd_) sc_core::sc_close_vcd_trace_file(vcd_);
    if (perfetto_.is_open()) perfetto_.close();
    std::error_code ignored;
    fs::remove(fs::path(options_.dir) / (vcd_temp() + ".vcd"), ignored);
    fs::remove(fs::path(options_.dir) / perfetto_temp(), ignored);
}

void Tracer::event_separator() {
    if (events_.size() >= kFlushBytes) flush_events();
    put(events_, first_event_ ? "\n" : ",\n");
    first_event_ = false;
}

// Through the stream, so that a failed stream (a full disk) only stops taking data.
void Tracer::flush_events() {
    perfetto_.write(events_.data(), std::streamsize(events_.size()));
    events_.clear();
}

int Tracer::group_id(const std::string& group) {
    for (size_t i = 0; i < groups_.size(); ++i)
        if (groups_[i] == group) return static_cast<int>(i) + 1;
    groups_.push_back(group);
    const int pid = static_cast<int>(groups_.size());
    auto out = std::back_inserter(events_);
    event_separator();
    fmt::format_to(out, R"({{"ph":"M","name":"process_name","pid":{},"tid":0,"args":{{"name":)", pid);
    put_json_string(events_, group);
    put(events_, "}}");
    event_separator();
    fmt::format_to(out, R"({{"ph":"M","name":"process_sort_index","pid":{},"tid":0,"args":{{"sort_index":{}}}}})", pid, pid);
    return pid;
}

int Tracer::track(const std::string& group, const std::string& name) {
    if (!perfetto_on()) return -1;
    const int pid = group_id(group);
    const int tid = static_cast<int>(tracks_.size()) + 1;
    tracks_.push_back({pid, tid, {}});
    auto out = std::back_inserter(events_);
    event_separator();
    fmt::format_to(out, R"({{"ph":"M","name":"thread_name","pid":{},"tid":{},"args":{{"name":)", pid, tid);
    put_json_string(events_, name);
    put(events_, "}}");
    event_separator();
    fmt::format_to(out, R"({{"ph":"M","name":"thread_sort_index","pid":{},"tid":{},"args":{{"sort_index":{}}}}})", pid, tid,
                   tid);
    return static_cast<int>(tracks_.size()) - 1;
}

void Tracer::slice(int track, std::string_view name, const sc_core::sc_time& start, const sc_core::sc_time& end) {
    if (!perfetto_on() || track < 0) return;
    const Track& t = tracks_[track];
    event_separator();
    put(events_, R"({"ph":"X","name":)");
    put_json_string(events_, name);
    fmt::format_to(std::back_inserter(events_), FMT_COMPILE(R"(,"pid":{},"tid":{},"ts":)"), t.pid, t.tid);
    put_micros(events_, start);
    put(events_, R"(,"dur":)");
    put_micros(events_, end - start);
    put(events_, "}");
}

void Tracer::counter(int track, std::string_view name, const sc_core::sc_time& at, double value) {
    if (!perfetto_on() || track < 0) return;
    auto& counters = tracks_[track].counters;
    auto last = std::find_if(counters.begin(), counters.end(), [&](const auto& c) { return c.first == name; });
    if (last == counters.end()) counters.emplace_back(std::string(name), value);
    else if (last->second == value) return;
    else last->second = value;
    event_separator();
    put(events_, R"({"ph":"C","name":)");
    put_json_string(events_, name);
    fmt::format_to(std::back_inserter(events_), FMT_COMPILE(R"(,"pid":{},"ts":)"), tracks_[track].pid);
    put_micros(events_, at);
    fmt::format_to(std::back_inserter(events_), FMT_COMPILE(R"(,"args":{{"value":{}}}}})"), value);
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

std::vector<std::string> Tracer::finish() {
    std::vector<std::string> written;
    const fs::path dir(options_.dir);
    if (vcd_) {
        sc_core::sc_close_vcd_trace_file(vcd_);
        vcd_ = nullptr;
        check_vcd_complete(dir / (vcd_temp() + ".vcd"));
        fs::rename(dir / (vcd_temp() + ".vcd"), dir / "trace.vcd");
        written.push_back((dir / "trace.vcd").string());
        for (const std::string& f : write_gtkwave_save(dir)) written.push_back(f);
    }
    if (perfetto_.is_open()) {
        flush_events();
        perfetto_ << "\n]}\n";
        perfetto_.close();
        if (!perfetto_) {
            std::error_code ignored;
            fs::remove(dir / perfetto_temp(), ignored);
            throw EnvironmentError((dir / "trace.perfetto.json").string() + ": the write failed (disk full?)");
        }
        fs::rename(dir / perfetto_temp(), dir / "trace.perfetto.json");
        written.push_back((dir / "trace.perfetto.json").string());
    }
    finished_ = true;
    return written;
}

}  // namespace surfvp
