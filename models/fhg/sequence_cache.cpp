#include "sequence_cache.h"

#include <fmt/format.h>
#include <functional>
#include <map>
#include <mutex>
#include <tuple>
#include <sstream>

#include "models/host/disk_cache.h"

#ifndef SURFVP_SEQUENCE_FINGERPRINT
#error "the build defines SURFVP_SEQUENCE_FINGERPRINT (models/CMakeLists.txt)"
#endif

namespace surfvp::fhg {
namespace fs = std::filesystem;

std::optional<fs::path> sequence_cache_folder() { return cache_folder(); }

std::string sequence_key(const SequenceParams& p) {
    return fmt::format(
        "generator {} read_buses {} triple_macs {} fifo_lines {} x3_cycles {} bus_word {} reuse {} "
        "line_fifo {} line_groups {} scheduler {} attempts {}",
        SURFVP_SEQUENCE_FINGERPRINT, p.read_buses, p.triple_macs, p.fifo_lines, p.x3_cycles, bus_word_name(p.bus_word),
        p.reuse, line_fifo_name(p.line_fifo), p.line_groups, scheduler_name(p.scheduler), p.attempts);
}

// Line 1 the key; line 2 the figures; then one line per step: cycle bus x y and its taps as
// (triple_mac lane coefficient response) fours.
std::string sequence_text(const std::string& key, const Sequence& s) {
    std::string out = key + "\n";
    out += fmt::format("{} {} {} {} {} {} {} {} {} {} {}\n", s.interval, s.span, s.optimal_cycles, s.spread[0],
                       s.spread[1], s.reads_per_block, s.distinct_reads_per_block, s.words_delivered, s.busy_bus_cycles,
                       s.steps.size(), s.optimal_limit.empty() ? "-" : s.optimal_limit);
    for (const Step& step : s.steps) {
        out += fmt::format("{} {} {} {} {}", step.cycle, step.bus, step.x, step.y, step.taps.size());
        for (const Tap& t : step.taps)
            out += fmt::format(" {} {} {} {}", t.triple_mac, t.lane, t.coefficient, int(t.response));
        out += "\n";
    }
    return out;
}

std::optional<Sequence> read_sequence_text(const std::string& text, const std::string& key) {
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line) || line != key) return std::nullopt;
    Sequence s;
    size_t steps = 0;
    if (!std::getline(in, line)) return std::nullopt;
    std::istringstream figures(line);
    figures >> s.interval >> s.span >> s.optimal_cycles >> s.spread[0] >> s.spread[1] >> s.reads_per_block >>
        s.distinct_reads_per_block >> s.words_delivered >> s.busy_bus_cycles >> steps;
    std::getline(figures >> std::ws, s.optimal_limit);  // the rest of the line: it may hold spaces
    if (!figures && !figures.eof()) return std::nullopt;
    if (s.optimal_limit == "-") s.optimal_limit.clear();
    for (size_t i = 0; i < steps; ++i) {
        Step step{};
        size_t taps = 0;
        if (!(in >> step.cycle >> step.bus >> step.x >> step.y >> taps) || taps > 64) return std::nullopt;
        for (size_t k = 0; k < taps; ++k) {
            Tap t{};
            int response = 0;
            if (!(in >> t.triple_mac >> t.lane >> t.coefficient >> response) || response < 0 || response > 2)
                return std::nullopt;
            t.response = Response(response);
            step.taps.push_back(t);
        }
        s.steps.push_back(std::move(step));
    }
    std::string rest;
    if (in >> rest) return std::nullopt;  // more than the steps it announced: not one of ours
    return s;
}

Sequence stored_sequence(const SequenceParams& params, const fs::path& folder) {
    const std::string key = sequence_key(params);
    if (const auto text = read_cached_in(folder, "sequence", key))  // an entry checked as the cache checks every one
        if (auto s = read_sequence_text(*text, key)) return *s;
    Sequence s = generate_sequence(params);
    write_cached_in(folder, "sequence", key, sequence_text(key, s));
    return s;
}

const Sequence& cached_sequence(const SequenceParams& p) {
    using Key = std::tuple<unsigned, unsigned, unsigned, unsigned, int, bool, int, unsigned, int, unsigned>;
    static std::map<Key, Sequence> cache;
    static std::mutex mutex;
    const Key key{p.read_buses, p.triple_macs,    p.fifo_lines,  p.x3_cycles,      int(p.bus_word),
                  p.reuse,      int(p.line_fifo), p.line_groups, int(p.scheduler), p.attempts};
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it == cache.end()) {
        const auto folder = sequence_cache_folder();
        it = cache.emplace(key, folder ? stored_sequence(p, *folder) : generate_sequence(p)).first;
    }
    return it->second;
}

}  // namespace surfvp::fhg
