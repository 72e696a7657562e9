#include "vcd_writer.h"

#include "models/host/atomic_file.h"

#include <algorithm>
#include <ctime>
#include <iterator>
#include <map>
#include <memory>
#include <utility>

namespace surfvp {
namespace {

constexpr size_t kDrainBytes = 1 << 20;  // the buffer goes to the file beyond this

// The n-th identifier: five letters, the last one counting fastest.
std::string identifier(size_t n) {
    std::string id(5, 'a');
    for (size_t i = id.size(); i-- > 0 && n; n /= 26) id[i] = char('a' + n % 26);
    return id;
}

// The signals as scopes: each dotted prefix a scope, its signals in the order added, then its
// scopes in name order.
struct Scope {
    std::vector<std::pair<std::string, size_t>> vars;  // leaf name, signal index
    std::map<std::string, std::unique_ptr<Scope>> children;
};

}  // namespace

VcdWriter::VcdWriter(const std::string& path) : out_(path, std::ios::binary | std::ios::trunc) {
    if (!out_) throw EnvironmentError("cannot write " + path);
}

int VcdWriter::add(const std::string& name, unsigned bits, uint64_t initial) {
    signals_.push_back({name, bits, identifier(signals_.size()), initial, initial});
    return int(signals_.size()) - 1;
}

void VcdWriter::change(int index, uint64_t value, uint64_t time_ps) {
    if (time_ps != pending_ps_) {
        flush();
        pending_ps_ = time_ps;
    }
    Signal& s = signals_[size_t(index)];
    s.value = value;
    if (!s.pending) s.pending = true, pending_.push_back(index);
}

void VcdWriter::header() {
    auto out = std::back_inserter(buffer_);
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%b %d, %Y       %H:%M:%S", std::localtime(&now));
    fmt::format_to(out, "$date\n     {}\n$end\n\n$version\n surfvp\n$end\n\n$timescale\n     1 ps\n$end\n\n", date);
    Scope top;
    for (size_t i = 0; i < signals_.size(); ++i) {
        Scope* scope = &top;
        const std::string& name = signals_[i].name;
        size_t from = 0;
        for (size_t dot; (dot = name.find('.', from)) != std::string::npos; from = dot + 1) {
            auto& child = scope->children[name.substr(from, dot - from)];
            if (!child) child = std::make_unique<Scope>();
            scope = child.get();
        }
        scope->vars.emplace_back(name.substr(from), i);
    }
    auto print = [&](auto& self, const std::string& name, const Scope& scope) -> void {
        fmt::format_to(out, "$scope module {} $end\n", name);
        for (const auto& [leaf, i] : scope.vars) {
            const Signal& s = signals_[i];
            if (s.bits == 1)
                fmt::format_to(out, "$var wire {:>4}  {}  {}       $end\n", 1, s.id, leaf);
            else
                fmt::format_to(out, "$var wire {:>4}  {}  {} [{}:0]  $end\n", s.bits, s.id, leaf, s.bits - 1);
        }
        for (const auto& [child, sub] : scope.children) self(self, child, *sub);
        fmt::format_to(out, "$upscope $end\n");
    };
    print(print, "SystemC", top);
    fmt::format_to(out,
                   "$enddefinitions  $end\n\n$comment\nAll initial values are dumped below at time 0 sec = 0 timescale "
                   "units.\n$end\n\n$dumpvars\n");
    for (Signal& s : signals_) {
        put_value(s);
        s.written = s.value, s.pending = false;
    }
    fmt::format_to(out, "$end\n");
    pending_.clear();
    started_ = true;
}

void VcdWriter::put_value(const Signal& s) {
    auto out = std::back_inserter(buffer_);
    if (s.bits == 1)
        fmt::format_to(out, "{}{}\n", s.value ? '1' : '0', s.id);
    else
        fmt::format_to(out, "b{:b} {}\n", s.value, s.id);
}

// The pending time step: the values at its end that differ from the last written, in the
// order the signals were added. Time 0's, with the values before it, are the initial values.
void VcdWriter::flush() {
    if (!started_) return header();  // the first step is time 0's: a change at a later time flushes it first
    std::sort(pending_.begin(), pending_.end());
    bool stamped = false;
    for (int index : pending_) {
        Signal& s = signals_[size_t(index)];
        s.pending = false;
        if (s.value == s.written) continue;
        if (!std::exchange(stamped, true)) stamp(pending_ps_);
        put_value(s);
        s.written = s.value;
    }
    pending_.clear();
    if (buffer_.size() > kDrainBytes) drain();
}

void VcdWriter::stamp(uint64_t ps) {
    fmt::format_to(std::back_inserter(buffer_), "\n#{}\n", ps);
    stamped_ps_ = ps;
}

void VcdWriter::drain() {
    out_.write(buffer_.data(),
               std::streamsize(buffer_.size()));  // a failed stream (a full disk) only stops taking data
    buffer_.clear();
}

bool VcdWriter::close(uint64_t end_ps) {
    flush();
    if (end_ps > stamped_ps_) stamp(end_ps);  // a reader sees how long the run was
    drain();
    out_.close();
    return bool(out_);
}

}  // namespace surfvp
