#include "sequence_generator.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace surfvp::fhg {
namespace {

using Point = std::pair<int, int>;  // (y, x): sorts row by row, as the line FIFO holds them

// One value a TripleMAC must take.
struct Need {
    int tm;
    int y, x;  // relative to the block's pixel (0, 0)
    int coefficient;
    Response response;
    int cost;
};

// The reads a word takes from the BRAMs: (BRAM index, reads from it), by BRAM.
using Ports = std::vector<std::pair<int, int>>;

// A word the buses can deliver: where it sits, whom it can serve, what it costs the BRAMs.
struct Word {
    int y, x;
    std::vector<int> needs;  // reuse: every need with a point in it; else the group's members
    Ports ports;             // a group's: the reads of the values its members take
};

struct Problem {
    std::vector<Need> needs;
    std::vector<int> work;     // per TripleMAC: cycles of additions
    std::vector<Word> groups;  // one delivery per group (no reuse), in the order of the block record
    std::vector<Word> words;   // every word inside the window holding a needed value (reuse)
    int brams = 0;             // lines x banks
    int distinct = 0;          // distinct integral points
};

bool in_window(int v) { return v >= -kReachBefore && v <= kReachAfter; }

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

int bram_of(const SequenceParams& p, int y, int x) {
    const int banks = line_fifo_shape(p.line_fifo).banks;
    return (y + kReachBefore) * banks + ((x % banks) + banks) % banks;
}

// The reads that deliver the values at `points` (y, x): one a value, or with 72-bit reads one
// an aligned pair, counted per BRAM.
Ports reads_of(const SequenceParams& p, const std::vector<Point>& points) {
    std::vector<std::pair<int, int>> units;  // (BRAM, the column or aligned pair it reads)
    for (const auto& [y, x] : points) {
        const LineRead r = line_read(p, y, x);
        units.emplace_back(r.bram, r.unit);
    }
    std::sort(units.begin(), units.end());
    units.erase(std::unique(units.begin(), units.end()), units.end());
    Ports ports;
    for (const auto& u : units) {
        if (!ports.empty() && ports.back().first == u.first)
            ++ports.back().second;
        else
            ports.emplace_back(u.first, 1);
    }
    return ports;
}

void validate(const SequenceParams& p) {
    if (p.read_buses < 1 || p.read_buses > 64)
        throw std::invalid_argument("fhg.read_buses must be 1 to 64, not " + std::to_string(p.read_buses));
    if (p.triple_macs < unsigned(kDeterminantsPerBlock))
        throw std::invalid_argument("fhg.triple_macs: " + std::to_string(p.triple_macs) + " is fewer than the " +
                                    std::to_string(kDeterminantsPerBlock) +
                                    " determinants of a block, and time-sharing a TripleMAC is not modelled");
    if (p.fifo_lines < unsigned(kWindow))
        throw std::invalid_argument("fhg.fifo_lines: " + std::to_string(p.fifo_lines) + " lines cannot hold the " +
                                    std::to_string(kWindow) + "-line window of the largest filter (51)");
    if (p.x3_cycles < 1 || p.x3_cycles > 8)
        throw std::invalid_argument("fhg.x3_cycles must be 1 to 8, not " + std::to_string(p.x3_cycles));
    const std::string groups = std::to_string(p.line_groups);
    if (p.line_groups != 1 && p.line_groups != 2 && p.line_groups != 4)
        throw std::invalid_argument("fhg.line_groups must be 1, 2 or 4, not " + groups);
    if (p.read_buses % p.line_groups)
        throw std::invalid_argument(
            "fhg.line_groups: " + groups + " groups need a multiple of " + groups +
            " read buses (each group its own), not fhg.read_buses = " + std::to_string(p.read_buses));
    if (p.fifo_lines % p.line_groups)
        throw std::invalid_argument("fhg.line_groups: " + groups + " groups must divide fhg.fifo_lines (" +
                                    std::to_string(p.fifo_lines) +
                                    "), or a line's group would change as the FIFO wraps");
}

// Every word the basic script must deliver has to be readable in one cycle: the reads it takes
// from one BRAM within what that BRAM serves.
void check_words_fit(const SequenceParams& p, const std::vector<Word>& groups) {
    const LineFifoShape f = line_fifo_shape(p.line_fifo);
    for (const Word& g : groups)
        for (const auto& [bram, reads] : g.ports)
            if (reads > f.reads)
                throw std::invalid_argument(std::string("fhg.line_fifo: ") + line_fifo_name(p.line_fifo) + " serves " +
                                            std::to_string(f.reads) + (f.aligned_pairs ? " aligned pair" : " read") +
                                            (f.reads > 1 ? "s" : "") + " of a line's BRAM a cycle, but a " +
                                            bus_word_name(p.bus_word) + " word at column " + std::to_string(g.x) +
                                            " needs " + std::to_string(reads) +
                                            "; choose another fhg.line_fifo or fhg.bus_word");
}

bool word_in_window(const SequenceParams& p, int y, int x) {
    for (const auto& [dy, dx] : word_shape(p.bus_word))
        if (!in_window(y + dy) || !in_window(x + dx)) return false;
    return true;
}

// Without reuse a word carries one read of the neighbouring pixels' determinants of one
// size: a quad the four pixels', a pair the two of one row; octave 2 (one pixel) goes alone.
std::tuple<int, int, int> group_key(const SequenceParams& p, int tm, int read, const BlockDeterminant& d) {
    if (tm >= 16 || p.bus_word == BusWord::scalar) return {tm, read, 0};
    if (p.bus_word == BusWord::pair) return {100 + d.size, read, d.py};
    return {100 + d.size, read, 0};
}

// Where a group's word sits: octave 1's with the pixel (0, 0) member in lane 0; octave 2's
// single value in the first lane that keeps the word inside the window.
Word group_word(const SequenceParams& p, const Need& need, const BlockDeterminant& d) {
    if (need.tm < 16 && p.bus_word != BusWord::scalar)
        return {need.y - (p.bus_word == BusWord::quad ? d.py : 0), need.x - d.px, {}, {}};
    for (const auto& [dy, dx] : word_shape(p.bus_word))
        if (word_in_window(p, need.y - dy, need.x - dx)) return {need.y - dy, need.x - dx, {}, {}};
    throw std::logic_error("sequence generator: no word holds a value inside the window");
}

Problem make_problem(const SequenceParams& p) {
    Problem problem;
    problem.work.assign(p.triple_macs, 0);
    problem.brams = kWindow * line_fifo_shape(p.line_fifo).banks;
    std::map<std::tuple<int, int, int>, int> group_of;
    std::map<Point, int> word_of;
    std::set<Point> points;
    for (int t = 0; t < kDeterminantsPerBlock; ++t) {
        const BlockDeterminant d = block_determinant(t);
        const std::vector<Read> reads = filter_reads(d.size);
        for (size_t j = 0; j < reads.size(); ++j) {
            const Read& r = reads[j];
            const int cost = (r.coefficient == 3 || r.coefficient == -3) ? int(p.x3_cycles) : 1;
            const int index = int(problem.needs.size());
            const Need need{t, d.py + r.dy, d.px + r.dx, r.coefficient, r.response, cost};
            problem.needs.push_back(need);
            problem.work[t] += cost;
            points.insert({need.y, need.x});
            const auto [it, fresh] = group_of.emplace(group_key(p, t, int(j), d), int(problem.groups.size()));
            if (fresh) problem.groups.push_back(group_word(p, need, d));
            problem.groups[size_t(it->second)].needs.push_back(index);
            for (const auto& [dy, dx] : word_shape(p.bus_word)) {
                const int y = need.y - dy, x = need.x - dx;
                if (!word_in_window(p, y, x)) continue;
                const auto [w, added] = word_of.emplace(Point{y, x}, int(problem.words.size()));
                if (added) problem.words.push_back({y, x, {}, {}});
                problem.words[size_t(w->second)].needs.push_back(index);
            }
        }
    }
    for (Word& g : problem.groups) {
        std::vector<Point> points;
        for (int i : g.needs) points.emplace_back(problem.needs[size_t(i)].y, problem.needs[size_t(i)].x);
        g.ports = reads_of(p, points);
    }
    std::sort(problem.words.begin(), problem.words.end(),
              [](const Word& a, const Word& b) { return std::tie(a.y, a.x) < std::tie(b.y, b.x); });
    problem.distinct = int(points.size());
    return problem;
}

int ceil_div(int a, int b) { return (a + b - 1) / b; }

// The lower bound and what sets it: TripleMAC work, bus words, or BRAM reads.
std::pair<int, std::string> lower_bound(const Problem& problem, const SequenceParams& p) {
    const int tm = *std::max_element(problem.work.begin(), problem.work.end());
    const int values = int(word_shape(p.bus_word).size());
    const int words = p.reuse ? ceil_div(problem.distinct, values) : int(problem.groups.size());
    int buses = ceil_div(words, int(p.read_buses));
    if (!p.reuse) {  // each line group's words on its own buses (a single value's may move: top_on_bus)
        std::vector<int> in_group(p.line_groups, 0);
        for (const Word& g : problem.groups)
            if (g.needs.size() > 1 || p.bus_word != BusWord::quad) ++in_group[size_t(line_group(p, g.y))];
        for (int n : in_group) buses = std::max(buses, ceil_div(n, int(p.read_buses / p.line_groups)));
    }
    std::vector<int> reads(size_t(problem.brams), 0);
    if (p.reuse) {
        std::vector<Point> points;
        for (const Need& n : problem.needs) points.emplace_back(n.y, n.x);
        for (const auto& [bram, n] : reads_of(p, points)) reads[size_t(bram)] += n;
    } else {
        for (const Word& g : problem.groups)
            for (const auto& [bram, n] : g.ports) reads[size_t(bram)] += n;
    }
    const auto busiest = std::max_element(reads.begin(), reads.end());
    const int ports = ceil_div(*busiest, line_fifo_shape(p.line_fifo).reads);
    const int bound = std::max({tm, buses, ports});
    std::vector<std::string> limits;
    if (tm == bound) limits.push_back("TripleMAC work");
    if (buses == bound) limits.push_back("read buses");
    if (ports == bound) {
        const int bram = int(busiest - reads.begin());
        limits.push_back("line FIFO ports (line " +
                         std::to_string(bram / line_fifo_shape(p.line_fifo).banks - kReachBefore) + ")");
    }
    std::string limit;
    for (const std::string& l : limits) limit += (limit.empty() ? "" : ", ") + l;
    return {bound, limit};
}

// The lane of word `w` that holds need `n`'s value.
int lane_of(const SequenceParams& p, const Need& n, const Word& w) {
    const auto& shape = word_shape(p.bus_word);
    for (size_t l = 0; l < shape.size(); ++l)
        if (w.y + shape[l][0] == n.y && w.x + shape[l][1] == n.x) return int(l);
    throw std::logic_error("sequence generator: a value outside its word");
}

// The machine's state while a scheduler fills cycles: who is busy, what each BRAM has served
// this cycle, what is still to deliver.
class Machine {
public:
    Machine(const Problem& problem, const SequenceParams& p)
        : problem_(problem),
          p_(p),
          pending_(problem.needs.size(), true),
          busy_until_(p.triple_macs, 0),
          claimed_at_(p.triple_macs, -1),
          remaining_(problem.work),
          port_read_(size_t(problem.brams * reads_), {-1, 0}),
          bram_left_(size_t(problem.brams), 0),
          left_(int(problem.needs.size())) {
        for (const Need& n : problem.needs) bram_left_[size_t(bram_of(p, n.y, n.x))] += 1;
    }

    bool done() const { return left_ == 0; }
    bool pending(int need) const { return pending_[size_t(need)]; }
    bool free(int tm, int cycle) const { return claimed_at_[size_t(tm)] != cycle && busy_until_[size_t(tm)] <= cycle; }
    int remaining(int tm) const { return remaining_[size_t(tm)]; }
    // Cycles the busiest BRAM these reads touch still needs for the values waiting on it.
    int bram_pressure(const Ports& ports) const {
        int most = 0;
        for (const auto& [bram, reads] : ports) most = std::max(most, bram_left_[size_t(bram)]);
        return (most + reads_ - 1) / reads_;
    }
    // Whether `bus` can read the values of `w` that `needs` take in `cycle`: each through the
    // port its lane is wired to (lane_port), which reads one unit a cycle, shared by every lane
    // that wants that unit.
    bool ports_fit(const Word& w, const std::vector<int>& needs, int bus, int cycle) const {
        mine_.clear();
        for (int i : needs) {
            const auto [port, unit] = port_read(w, i, bus);
            const auto& [at, read] = port_read_[size_t(port)];
            if (at == cycle && read != unit) return false;
            for (const auto& [other, other_unit] : mine_)
                if (other == port && other_unit != unit) return false;
            mine_.emplace_back(port, unit);
        }
        return true;
    }

    // Delivers `w` on `bus` in `cycle` to the given needs.
    void deliver(const Word& w, const std::vector<int>& needs, int cycle, int bus, std::vector<Step>& steps) {
        Step step{cycle, bus, w.x, w.y, {}};
        for (int i : needs) {
            const Need& n = problem_.needs[size_t(i)];
            pending_[size_t(i)] = false;
            claimed_at_[size_t(n.tm)] = cycle;
            busy_until_[size_t(n.tm)] = cycle + n.cost;
            remaining_[size_t(n.tm)] -= n.cost;
            bram_left_[size_t(bram_of(p_, n.y, n.x))] -= 1;
            step.taps.push_back({n.tm, lane_of(p_, n, w), n.coefficient, n.response});
        }
        for (int i : needs) {
            const auto [port, unit] = port_read(w, i, bus);
            port_read_[size_t(port)] = {cycle, unit};
        }
        left_ -= int(needs.size());
        steps.push_back(std::move(step));
    }

private:
    // Need `i`'s read as word `w` on `bus` makes it: (the BRAM port, numbered BRAM x reads +
    // port, and the unit it reads).
    std::pair<int, int> port_read(const Word& w, int i, int bus) const {
        const Need& n = problem_.needs[size_t(i)];
        const LineRead r = line_read(p_, n.y, n.x);
        return {r.bram * reads_ + lane_port(p_, bus, lane_of(p_, n, w)), r.unit};
    }

    const Problem& problem_;
    const SequenceParams& p_;
    int reads_ = line_fifo_shape(p_.line_fifo).reads;  // per BRAM and FHG cycle
    std::vector<bool> pending_;
    std::vector<int> busy_until_, claimed_at_, remaining_;
    std::vector<std::pair<int, int>> port_read_;  // per BRAM port: the cycle it last read, and what
    std::vector<int> bram_left_;
    int left_;
    mutable std::vector<std::pair<int, int>> mine_;  // ports_fit's scratch: this word's reads
};

constexpr int kNoTop = -1000;  // no top line puts the word on the bus

// The top line at which `bus` can carry word `w`: its own, or for a group whose values all lie
// on one line of a quad word (octave 2's single values), the line above it, the value then in
// the word's lower lanes, where the bus reaches the other group (fhg.line_groups); else kNoTop.
int top_on_bus(const SequenceParams& p, const Problem& problem, const Word& w, int bus, bool reuse) {
    if (bus_reaches(p, bus, w.y)) return w.y;
    if (reuse || p.bus_word != BusWord::quad) return kNoTop;
    for (int i : w.needs)
        if (problem.needs[size_t(i)].y != w.y) return kNoTop;
    const int up = w.y - 1;
    return bus_reaches(p, bus, up) && word_in_window(p, up, w.x) ? up : kNoTop;
}

constexpr int kCycleLimit = 1 << 16;  // far beyond any schedule; a guard against a scheduler bug

// One pass of the list scheduler both scripts use: each bus carries the word whose free
// consumers have the most work left (the most loaded TripleMAC decides the length; with
// `port_aware`, also the most loaded BRAM it reads), then the one serving the most, then a
// seeded jitter (seed 0: none).
std::vector<Step> schedule_list(const Problem& problem, const SequenceParams& p, bool reuse, unsigned seed,
                                bool port_aware = false) {
    Machine m(problem, p);
    std::mt19937 rng(seed);
    std::vector<Step> steps;
    const std::vector<Word>& candidates = reuse ? problem.words : problem.groups;
    std::vector<int> alive(candidates.size());
    for (size_t i = 0; i < alive.size(); ++i) alive[i] = int(i);
    std::vector<int> served, taken, best_served, slot(p.triple_macs, -1);
    std::vector<Point> points;
    Ports ports;
    for (int cycle = 0; !m.done(); ++cycle) {
        if (cycle > kCycleLimit) throw std::logic_error("sequence generator: the list schedule does not end");
        for (unsigned bus = 0; bus < p.read_buses; ++bus) {
            long best_score = 0;
            int best = -1, best_top = 0;
            for (size_t a = 0; a < alive.size();) {
                const Word& w = candidates[size_t(alive[a])];
                bool any = false;
                served.clear();
                for (int i : w.needs) {
                    if (!m.pending(i)) continue;
                    any = true;
                    const int tm = problem.needs[size_t(i)].tm;
                    if (!m.free(tm, cycle)) continue;
                    // One value per TripleMAC: the costliest of those this word holds for it.
                    if (slot[size_t(tm)] >= 0 &&
                        problem.needs[size_t(slot[size_t(tm)])].cost >= problem.needs[size_t(i)].cost)
                        continue;
                    if (slot[size_t(tm)] < 0) served.push_back(tm);
                    slot[size_t(tm)] = i;
                }
                if (!any) {  // nothing left to deliver in this word
                    alive[a] = alive.back();
                    alive.pop_back();
                    continue;
                }
                const int top = top_on_bus(p, problem, w, int(bus), reuse);
                if (top == kNoTop) {  // its lines are another group's
                    for (int tm : served) slot[size_t(tm)] = -1;
                    ++a;
                    continue;
                }
                Word moved;  // the word as this bus carries it
                if (top != w.y) moved = {top, w.x, w.needs, w.ports};
                const Word& carried = top == w.y ? w : moved;
                // A group goes whole or not at all.
                const bool whole = reuse || served.size() == w.needs.size();
                if (reuse && !served.empty()) {  // a shared word reads the values it is taken for
                    points.clear();
                    for (int tm : served)
                        points.emplace_back(problem.needs[size_t(slot[size_t(tm)])].y,
                                            problem.needs[size_t(slot[size_t(tm)])].x);
                    ports = reads_of(p, points);
                }
                const Ports& reads = reuse ? ports : w.ports;
                taken.clear();
                for (int tm : served) taken.push_back(slot[size_t(tm)]);
                if (!served.empty() && whole && m.ports_fit(carried, taken, int(bus), cycle)) {
                    long most = 0;
                    for (int tm : served) most = std::max<long>(most, m.remaining(tm));
                    if (port_aware) most = std::max<long>(most, m.bram_pressure(reads));
                    const long score = most * 1000000 + long(served.size()) * 1000 + (seed ? long(rng() % 1000) : 0);
                    if (score > best_score) {
                        best_score = score;
                        best = alive[a];
                        best_top = top;
                        best_served = taken;
                    }
                }
                for (int tm : served) slot[size_t(tm)] = -1;
                ++a;
            }
            if (best < 0) continue;  // nothing this bus could deliver this cycle
            Word chosen = candidates[size_t(best)];
            chosen.y = best_top;
            m.deliver(chosen, best_served, cycle, int(bus), steps);
        }
    }
    return steps;
}

Sequence finish(std::vector<Step> steps, const Problem& problem, const SequenceParams& p) {
    Sequence s;
    std::sort(steps.begin(), steps.end(),
              [](const Step& a, const Step& b) { return std::tie(a.cycle, a.bus) < std::tie(b.cycle, b.bus); });
    std::vector<int> first(p.triple_macs, -1), last(p.triple_macs, 0);
    for (const Step& step : steps) {
        s.interval = std::max(s.interval, step.cycle + 1);
        for (const Tap& t : step.taps) {
            const int end = step.cycle + (std::abs(t.coefficient) == 3 ? int(p.x3_cycles) : 1);
            if (first[size_t(t.triple_mac)] < 0) first[size_t(t.triple_mac)] = step.cycle;
            last[size_t(t.triple_mac)] = std::max(last[size_t(t.triple_mac)], end);
            s.span = std::max(s.span, end);
        }
    }
    // The next block may start once every TripleMAC can take its first value after its last
    // addition of this block.
    for (unsigned t = 0; t < p.triple_macs; ++t)
        if (first[t] >= 0) s.interval = std::max(s.interval, last[t] - first[t]);
    s.steps = std::move(steps);
    s.words_delivered = int(s.steps.size());
    s.reads_per_block = int(problem.needs.size());
    s.distinct_reads_per_block = problem.distinct;
    return s;
}

// One greedy pass per seed 1..attempts, the intervals sorted: the middle one is the basic
// script's (its ties are arbitrary, so a single pass is a draw from this spread).
std::vector<Sequence> single_passes(const Problem& problem, const SequenceParams& p, bool reuse, bool port_aware) {
    std::vector<Sequence> passes;
    for (unsigned seed = 1; seed <= std::max(1u, p.attempts); ++seed)
        passes.push_back(finish(schedule_list(problem, p, reuse, seed, port_aware), problem, p));
    std::stable_sort(passes.begin(), passes.end(),
                     [](const Sequence& a, const Sequence& b) { return a.interval < b.interval; });
    return passes;
}

Sequence schedule_basic(const Problem& problem, const SequenceParams& p) {
    std::vector<Sequence> passes = single_passes(problem, p, false, false);
    Sequence s = std::move(passes[(passes.size() - 1) / 2]);
    s.spread = {passes.front().interval, passes.back().interval};
    return s;
}

// The improved script: the shortest of the port-aware passes, with reuse where the machine
// allows it and without.
Sequence schedule_improved(const Problem& problem, const SequenceParams& p) {
    Sequence best;
    for (bool reuse : {false, true}) {
        if (reuse && !p.reuse) break;
        Sequence s = std::move(single_passes(problem, p, reuse, true).front());
        if (best.interval == 0 || s.interval < best.interval) best = std::move(s);
    }
    return best;
}

// Without reuse a word is one group's delivery: the same read (size, place relative to each
// pixel, coefficient, response) of every pixel the word serves, in full.
std::string check_one_group(const Step& step, const SequenceParams& p) {
    const auto& shape = word_shape(p.bus_word);
    std::set<std::tuple<int, int, int, int, int>> reads;
    std::set<int> tms;
    for (const Tap& tap : step.taps) {
        if (tap.triple_mac < 0 || tap.triple_mac >= kDeterminantsPerBlock || tap.lane < 0 ||
            tap.lane >= int(shape.size()))
            return "a tap outside the block's determinants or the word's lanes";
        const BlockDeterminant d = block_determinant(tap.triple_mac);
        reads.insert({d.size, step.x + shape[size_t(tap.lane)][1] - d.px, step.y + shape[size_t(tap.lane)][0] - d.py,
                      tap.coefficient, int(tap.response)});
        tms.insert(tap.triple_mac);
    }
    const int tm = step.taps.empty() ? 0 : step.taps.front().triple_mac;
    const size_t members = tm >= 16 || p.bus_word == BusWord::scalar ? 1 : p.bus_word == BusWord::pair ? 2 : 4;
    if (reads.size() > 1 || tms.size() != step.taps.size() || step.taps.size() != members)
        return "without reuse, a word that is not one read of its pixels' determinants of one size";
    return "";
}

}  // namespace

LineBram line_bram(LineFifo fifo, unsigned line_words) {
    const LineFifoShape shape = line_fifo_shape(fifo);
    const unsigned columns = unsigned(shape.banks) * (shape.aligned_pairs ? 2 : 1);  // a word covers, over the banks
    LineBram b{(line_words + columns - 1) / columns, 1};
    while ((1u << b.address_bits) < b.words) ++b.address_bits;
    return b;
}

int line_group(const SequenceParams& params, int y) {
    const int g = int(params.line_groups);
    return ((y + kReachBefore) % g + g) % g;
}

bool bus_reaches(const SequenceParams& params, int bus, int y) {
    return bus % int(params.line_groups) == line_group(params, y);
}

int lane_port(const SequenceParams& params, int bus, int lane) {
    const int dx = word_shape(params.bus_word)[size_t(lane)][1];
    const int columns = params.bus_word == BusWord::scalar ? 1 : 2;
    return (bus * columns + dx) % line_fifo_shape(params.line_fifo).reads;
}

LineRead line_read(const SequenceParams& params, int y, int x) {
    return {bram_of(params, y, x), line_fifo_shape(params.line_fifo).aligned_pairs ? floor_div(x, 2) : x};
}

const std::vector<std::array<int, 2>>& word_shape(BusWord word) {
    static const std::vector<std::array<int, 2>> scalar{{0, 0}}, pair{{0, 0}, {0, 1}},
        quad{{0, 0}, {0, 1}, {1, 0}, {1, 1}};
    return word == BusWord::scalar ? scalar : word == BusWord::pair ? pair : quad;
}

const char* bus_word_name(BusWord word) {
    switch (word) {
        case BusWord::scalar:
            return "scalar";
        case BusWord::pair:
            return "pair";
        case BusWord::quad:
            return "quad";
    }
    return "?";
}

const char* scheduler_name(Scheduler scheduler) { return scheduler == Scheduler::basic ? "basic" : "improved"; }

LineFifoShape line_fifo_shape(LineFifo fifo) {
    switch (fifo) {
        case LineFifo::tdp:
            return {1, 2, false, 1};
        case LineFifo::tdp_x2:
            return {1, 4, false, 2};
        case LineFifo::banked:
            return {2, 2, false, 1};
        case LineFifo::sdp72:
            return {1, 1, true, 1};
    }
    return {1, 2, false, 1};
}

const char* line_fifo_name(LineFifo fifo) {
    switch (fifo) {
        case LineFifo::tdp:
            return "tdp";
        case LineFifo::tdp_x2:
            return "tdp_x2";
        case LineFifo::banked:
            return "banked";
        case LineFifo::sdp72:
            return "sdp72";
    }
    return "?";
}

Sequence generate_sequence(const SequenceParams& params) {
    validate(params);
    const Problem problem = make_problem(params);
    check_words_fit(params, problem.groups);
    Sequence s =
        params.scheduler == Scheduler::basic ? schedule_basic(problem, params) : schedule_improved(problem, params);
    std::tie(s.optimal_cycles, s.optimal_limit) = lower_bound(problem, params);
    s.busy_bus_cycles = ceil_div(s.words_delivered, int(params.read_buses));
    return s;
}

namespace {

std::string describe(const std::tuple<int, int, int, int>& v) {
    static const char* const kResponses[] = {"Dxx", "Dyy", "Dxy"};
    const auto [x, y, coefficient, response] = v;
    return "I(" + std::to_string(x) + ", " + std::to_string(y) + ") x " + (coefficient > 0 ? "+" : "") +
           std::to_string(coefficient) + " into " + kResponses[response];
}

// The first value a TripleMAC lacks and the first it gets without needing it, in words.
std::string read_difference(const std::multiset<std::tuple<int, int, int, int>>& wanted,
                            const std::multiset<std::tuple<int, int, int, int>>& got) {
    std::vector<std::tuple<int, int, int, int>> missing, extra;
    std::set_difference(wanted.begin(), wanted.end(), got.begin(), got.end(), std::back_inserter(missing));
    std::set_difference(got.begin(), got.end(), wanted.begin(), wanted.end(), std::back_inserter(extra));
    std::string why;
    if (!missing.empty()) why += ": it misses " + describe(missing.front());
    if (!extra.empty()) why += std::string(missing.empty() ? ": it" : " and") + " gets " + describe(extra.front());
    if (missing.size() + extra.size() > 2)
        why += " (" + std::to_string(missing.size() + extra.size()) + " values differ)";
    return why;
}

}  // namespace

std::string check_sequence(const Sequence& sequence, const SequenceParams& params) {
    // What each TripleMAC must receive: (point, coefficient, response), as a multiset.
    using Value = std::tuple<int, int, int, int>;
    std::vector<std::multiset<Value>> wanted(params.triple_macs), got(params.triple_macs);
    for (int t = 0; t < kDeterminantsPerBlock; ++t) {
        const BlockDeterminant d = block_determinant(t);
        for (const Read& r : filter_reads(d.size))
            wanted[size_t(t)].insert({d.px + r.dx, d.py + r.dy, r.coefficient, int(r.response)});
    }
    std::vector<Step> steps = sequence.steps;
    std::stable_sort(steps.begin(), steps.end(), [](const Step& a, const Step& b) { return a.cycle < b.cycle; });
    const auto& shape = word_shape(params.bus_word);
    const LineFifoShape fifo = line_fifo_shape(params.line_fifo);
    std::vector<int> busy_until(params.triple_macs, 0), last_cycle(params.triple_macs, -1),
        first(params.triple_macs, -1);
    std::map<std::pair<int, int>, int> bus_use;           // (cycle, bus) -> words
    std::map<std::tuple<int, int, int>, int> port_reads;  // (cycle, BRAM, port) -> the unit it reads
    for (const Step& step : steps) {
        const std::string where = " in cycle " + std::to_string(step.cycle);
        if (step.bus < 0 || step.bus >= int(params.read_buses)) return "a step uses bus " + std::to_string(step.bus);
        if (step.cycle < 0 || step.cycle >= sequence.interval) return "a word outside the block's interval" + where;
        if (++bus_use[{step.cycle, step.bus}] > 1)
            return "bus " + std::to_string(step.bus) + " carries two words" + where;
        for (const auto& [dy, dx] : shape)
            if (!in_window(step.y + dy) || !in_window(step.x + dx)) return "a word outside the 52-line window" + where;
        if (!bus_reaches(params, step.bus, step.y))
            return "bus " + std::to_string(step.bus) + " reaches line group " +
                   std::to_string(step.bus % int(params.line_groups)) + " only, but its word's top line " +
                   std::to_string(step.y + kReachBefore) + " is in group " +
                   std::to_string(line_group(params, step.y)) + where;
        for (const Tap& tap : step.taps) {
            if (tap.lane < 0 || tap.lane >= int(shape.size())) continue;
            const LineRead r =
                line_read(params, step.y + shape[size_t(tap.lane)][0], step.x + shape[size_t(tap.lane)][1]);
            const int port = lane_port(params, step.bus, tap.lane);
            const auto [read, fresh] = port_reads.emplace(std::make_tuple(step.cycle, r.bram, port), r.unit);
            if (!fresh && read->second != r.unit)
                return "line " + std::to_string(r.bram / fifo.banks - kReachBefore) + " (BRAM " +
                       std::to_string(r.bram % fifo.banks) + ") port " + std::to_string(port) + " reads two addresses" +
                       where;
        }
        if (!params.reuse) {
            const std::string why = check_one_group(step, params);
            if (!why.empty()) return why + where;
        }
        for (const Tap& tap : step.taps) {
            const std::string who = "TripleMAC " + std::to_string(tap.triple_mac) + where;
            if (tap.triple_mac < 0 || tap.triple_mac >= int(params.triple_macs)) return "no " + who;
            if (tap.lane < 0 || tap.lane >= int(shape.size())) return who + " takes a lane the word does not have";
            if (last_cycle[size_t(tap.triple_mac)] == step.cycle) return who + " takes two values";
            if (busy_until[size_t(tap.triple_mac)] > step.cycle) return who + " is still busy with a x3";
            got[size_t(tap.triple_mac)].insert({step.x + shape[size_t(tap.lane)][1],
                                                step.y + shape[size_t(tap.lane)][0], tap.coefficient,
                                                int(tap.response)});
            if (first[size_t(tap.triple_mac)] < 0) first[size_t(tap.triple_mac)] = step.cycle;
            last_cycle[size_t(tap.triple_mac)] = step.cycle;
            busy_until[size_t(tap.triple_mac)] =
                step.cycle + (std::abs(tap.coefficient) == 3 ? int(params.x3_cycles) : 1);
        }
    }
    for (unsigned t = 0; t < params.triple_macs; ++t) {
        if (wanted[t] != got[t])
            return "TripleMAC " + std::to_string(t) + " does not receive exactly its reads" +
                   read_difference(wanted[t], got[t]);
        if (first[t] >= 0 && busy_until[t] > sequence.interval + first[t])
            return "TripleMAC " + std::to_string(t) + " is still adding when the next block hands it its first value";
    }
    return "";
}

}  // namespace surfvp::fhg
