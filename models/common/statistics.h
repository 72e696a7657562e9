#pragma once
// The statistics registry: at elaboration each module registers its named figures (what it
// counts, the bytes it moved, the time it spent, its high-water marks and maxima, its
// histograms), each with a unit and a meaning; at the end of the run one generic path reads
// them all into report.json and one renders them into report.md. A module keeps its own
// counters; the registry holds how to read them.
#include <cstdint>
#include <functional>
#include <string>
#include <systemc>
#include <utility>
#include <vector>

#include "time_series.h"

namespace surfvp {

enum class StatKind {
    count,       // events, items (an integer)
    bytes,       // bytes moved (an integer)
    time,        // time spent, in seconds
    high_water,  // the highest level a queue or FIFO reached (an integer)
    max,         // the largest single value seen (a time, in seconds)
    ratio,       // a share of the run's time (0..1)
    value,       // a figure of the configuration the run used (a clock, a width)
    text,        // a named choice the run used
    histogram,   // counts by bin
    series,      // a figure per time bin over the run (a busy share, a level)
};
inline const char* stat_kind_name(StatKind kind) {
    switch (kind) {
        case StatKind::count:
            return "count";
        case StatKind::bytes:
            return "bytes";
        case StatKind::time:
            return "time";
        case StatKind::high_water:
            return "high-water";
        case StatKind::max:
            return "max";
        case StatKind::ratio:
            return "ratio";
        case StatKind::value:
            return "value";
        case StatKind::text:
            return "text";
        case StatKind::histogram:
            return "histogram";
        case StatKind::series:
            return "series";
    }
    return "?";
}

struct Statistic {
    std::string path;  // "fhg.maxima_fifo_high_water": '.' separates levels, a number an instance
    StatKind kind;
    std::string unit;  // "s", "B", "candidates", ...
    std::string meaning;
    std::function<double(double elapsed_s)> number;  // all kinds but text and histogram
    std::function<std::string()> text;
    std::function<std::vector<std::pair<std::string, uint64_t>>()> bins;
    const TimeSeries* series = nullptr;  // read at the end: its bins widen as a long run goes on
};

class Statistics {
public:
    // Registers under a prefix ("plb1", "iig.0"): what a module sees of the registry.
    class Scope {
    public:
        Scope(Statistics& registry, std::string prefix) : registry_(registry), prefix_(std::move(prefix)) {}
        Scope operator/(const std::string& level) const { return {registry_, path(level)}; }

        void count(const std::string& name, std::function<uint64_t()> get, const std::string& unit,
                   const std::string& meaning) const {
            add(name, StatKind::count, unit, meaning, [get = std::move(get)](double) { return double(get()); });
        }
        void bytes(const std::string& name, std::function<uint64_t()> get, const std::string& meaning) const {
            add(name, StatKind::bytes, "B", meaning, [get = std::move(get)](double) { return double(get()); });
        }
        void high_water(const std::string& name, std::function<uint64_t()> get, const std::string& unit,
                        const std::string& meaning) const {
            add(name, StatKind::high_water, unit, meaning, [get = std::move(get)](double) { return double(get()); });
        }
        using Time = std::function<sc_core::sc_time()>;
        void time(const std::string& name, Time get, const std::string& meaning) const {
            add(name, StatKind::time, "s", meaning, [get = std::move(get)](double) { return get().to_seconds(); });
        }
        void max_time(const std::string& name, Time get, const std::string& meaning) const {
            add(name, StatKind::max, "s", meaning, [get = std::move(get)](double) { return get().to_seconds(); });
        }
        // A share of the run: the time `get` gives over the run's simulated time.
        void share(const std::string& name, Time get, const std::string& meaning) const {
            add(name, StatKind::ratio, "", meaning,
                [get = std::move(get)](double elapsed) { return elapsed > 0 ? get().to_seconds() / elapsed : 0.0; });
        }
        void value(const std::string& name, double v, const std::string& unit, const std::string& meaning) const {
            add(name, StatKind::value, unit, meaning, [v](double) { return v; });
        }
        void text(const std::string& name, std::function<std::string()> get, const std::string& meaning) const {
            Statistic s{path(name), StatKind::text, "", meaning, {}, std::move(get), {}, nullptr};
            registry_.all_.push_back(std::move(s));
        }
        void histogram(const std::string& name, std::function<std::vector<std::pair<std::string, uint64_t>>()> get,
                       const std::string& unit, const std::string& meaning) const {
            Statistic s{path(name), StatKind::histogram, unit, meaning, {}, {}, std::move(get), nullptr};
            registry_.all_.push_back(std::move(s));
        }
        void series(const std::string& name, const TimeSeries& series, const std::string& unit,
                    const std::string& meaning) const {
            Statistic s{path(name), StatKind::series, unit, meaning, {}, {}, {}, &series};
            registry_.all_.push_back(std::move(s));
        }

    private:
        std::string path(const std::string& name) const { return prefix_.empty() ? name : prefix_ + "." + name; }
        void add(const std::string& name, StatKind kind, const std::string& unit, const std::string& meaning,
                 std::function<double(double)> number) const {
            registry_.all_.push_back({path(name), kind, unit, meaning, std::move(number), {}, {}, nullptr});
        }
        Statistics& registry_;
        std::string prefix_;
    };

    Scope scope(const std::string& prefix) { return {*this, prefix}; }
    const std::vector<Statistic>& all() const { return all_; }

private:
    std::vector<Statistic> all_;
};

}  // namespace surfvp
