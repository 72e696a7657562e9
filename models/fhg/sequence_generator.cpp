#include "sequence_generator.h"

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace surfvp::fhg {
namespace {

using Point = std::pair<int, int>;  // (y, x): sorts row by row, as the line FIFO holds them

// One value a TripleMAC must take.
struct Need {
    int tm;
    Point point;  // absolute, relative to the block's pixel (0, 0)
    int coefficient;
    Response response;
    int cost;
    int group;  // without reuse: the need travels with the other members of its group
};

struct Problem {
    std::vector<Need> needs;
    std::vector<int> work;  // per TripleMAC: cycles of additions
    int groups = 0;
};

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
}

Problem make_problem(const SequenceParams& p) {
    Problem problem;
    problem.work.assign(p.triple_macs, 0);
    std::map<std::pair<int, int>, int> group_of;  // (size, read index) -> group, for quad octave 1
    for (int t = 0; t < kDeterminantsPerBlock; ++t) {
        const BlockDeterminant d = block_determinant(t);
        const std::vector<Read> reads = filter_reads(d.size);
        for (size_t j = 0; j < reads.size(); ++j) {
            const Read& r = reads[j];
            const int cost = (r.coefficient == 3 || r.coefficient == -3) ? int(p.x3_cycles) : 1;
            int group = problem.groups;
            // A quad word carries one read of all four pixels' determinants of a size at once.
            if (p.bus_word == BusWord::quad && t < 16) {
                auto [it, fresh] = group_of.emplace(std::make_pair(d.size, int(j)), problem.groups);
                group = it->second;
                if (fresh) ++problem.groups;
            } else {
                ++problem.groups;
            }
            problem.needs.push_back({t, {d.py + r.dy, d.px + r.dx}, r.coefficient, r.response, cost, group});
            problem.work[t] += cost;
        }
    }
    return problem;
}

// The words that can carry a point: itself (scalar) or the four quads containing it.
std::vector<Point> words_for(const Point& point, BusWord word) {
    if (word == BusWord::scalar) return {point};
    return {{point.first - 1, point.second - 1}, {point.first - 1, point.second}, {point.first, point.second - 1}, point};
}

int lane(const Point& point, const Point& word) { return 2 * (point.first - word.first) + (point.second - word.second); }

int lower_bound(const Problem& problem, const SequenceParams& p) {
    const int tm_bound = *std::max_element(problem.work.begin(), problem.work.end());
    std::set<Point> points;
    for (const Need& n : problem.needs) points.insert(n.point);
    int words = problem.groups;  // without reuse, every group is a delivery
    if (p.reuse) words = p.bus_word == BusWord::quad ? (int(points.size()) + 3) / 4 : int(points.size());
    return std::max(tm_bound, (words + int(p.read_buses) - 1) / int(p.read_buses));
}

class Scheduler {
public:
    Scheduler(const Problem& problem, const SequenceParams& p, unsigned seed)
        : problem_(problem), p_(p), pending_(problem.needs.size(), true), seed_(seed), rng_(seed) {
        busy_until_.assign(p.triple_macs, 0);
        remaining_ = problem.work;
        for (size_t i = 0; i < problem.needs.size(); ++i) {
            const Need& n = problem.needs[i];
            if (p.reuse) {
                for (const Point& w : words_for(n.point, p.bus_word)) by_word_[w].push_back(int(i));
            } else {
                // The group's canonical word: the first member's point minus its lane offset.
                const BlockDeterminant d = block_determinant(n.tm);
                const Point w = (p.bus_word == BusWord::quad && n.tm < 16) ? Point{n.point.first - d.py, n.point.second - d.px}
                                                                           : n.point;
                group_word_.emplace(n.group, w);
                by_group_[n.group].push_back(int(i));
            }
        }
    }

    Sequence run() {
        Sequence s;
        int left = int(problem_.needs.size());
        for (int cycle = 0; left > 0; ++cycle) {
            std::vector<bool> claimed(p_.triple_macs, false);
            for (int bus = 0; bus < int(p_.read_buses); ++bus) {
                Step step = best_step(cycle, claimed);
                if (step.taps.empty()) break;  // nothing any bus could deliver this cycle
                step.bus = bus;
                left -= int(step.taps.size());
                s.steps.push_back(std::move(step));
            }
        }
        for (const Step& step : s.steps)
            for (const Tap& t : step.taps)
                s.cycles = std::max(s.cycles, step.cycle + (std::abs(t.coefficient) == 3 ? int(p_.x3_cycles) : 1));
        s.words_delivered = int(s.steps.size());
        return s;
    }

private:
    bool free(int tm, int cycle, const std::vector<bool>& claimed) const { return !claimed[tm] && busy_until_[tm] <= cycle; }

    // Needs of `candidates` this word would serve now: one per free TripleMAC, the costliest.
    std::vector<int> servable(const std::vector<int>& candidates, int cycle, const std::vector<bool>& claimed) const {
        std::map<int, int> best;  // tm -> need
        for (int i : candidates) {
            if (!pending_[i]) continue;
            const Need& n = problem_.needs[i];
            if (!free(n.tm, cycle, claimed)) continue;
            auto it = best.find(n.tm);
            if (it == best.end() || n.cost > problem_.needs[it->second].cost) best[n.tm] = i;
        }
        std::vector<int> out;
        for (const auto& [tm, i] : best) out.push_back(i);
        return out;
    }

    // The most loaded TripleMAC served decides the makespan, so it ranks first; the number of
    // TripleMACs a word serves at once (reuse) breaks ties, then the attempt's seeded jitter.
    long score(const std::vector<int>& needs) {
        long most = 0;
        for (int i : needs) most = std::max<long>(most, remaining_[problem_.needs[i].tm]);
        const long jitter = seed_ ? long(rng_() % 1000) : 0;
        return most * 1000000 + long(needs.size()) * 1000 + jitter;
    }

    Step best_step(int cycle, std::vector<bool>& claimed) {
        long best_score = 0;
        Point best_word{};
        std::vector<int> best_needs;
        auto consider = [&](const Point& word, std::vector<int> needs) {
            const long s = score(needs);
            if (s > best_score) {
                best_score = s;
                best_word = word;
                best_needs = std::move(needs);
            }
        };
        if (p_.reuse) {
            for (const auto& [word, candidates] : by_word_) consider(word, servable(candidates, cycle, claimed));
        } else {
            for (const auto& [group, members] : by_group_) {
                std::vector<int> needs = servable(members, cycle, claimed);
                size_t pending = 0;
                for (int i : members) pending += pending_[i];
                if (needs.size() == pending && pending > 0) consider(group_word_.at(group), std::move(needs));
            }
        }
        Step step{cycle, 0, best_word.second, best_word.first, {}};
        for (int i : best_needs) {
            const Need& n = problem_.needs[i];
            pending_[i] = false;
            claimed[n.tm] = true;
            busy_until_[n.tm] = cycle + n.cost;
            remaining_[n.tm] -= n.cost;
            const int l = p_.bus_word == BusWord::quad ? lane(n.point, best_word) : 0;
            step.taps.push_back({n.tm, l, n.coefficient, n.response});
        }
        return step;
    }

    const Problem& problem_;
    const SequenceParams& p_;
    std::vector<bool> pending_;
    std::vector<int> busy_until_, remaining_;
    std::map<Point, std::vector<int>> by_word_;
    std::map<int, std::vector<int>> by_group_;
    std::map<int, Point> group_word_;
    unsigned seed_;
    std::mt19937 rng_;
};

}  // namespace

namespace {

// The plain greedy (attempt 0), then attempts whose ties are broken by seeded jitter; the
// shortest wins. Deterministic: the seeds are the attempt numbers.
Sequence best_of_attempts(const Problem& problem, const SequenceParams& params) {
    const int bound = lower_bound(problem, params);
    Sequence s = Scheduler(problem, params, 0).run();
    for (unsigned attempt = 1; attempt < params.attempts && s.cycles > bound; ++attempt) {
        Sequence candidate = Scheduler(problem, params, attempt).run();
        if (candidate.cycles < s.cycles) s = std::move(candidate);
    }
    return s;
}

}  // namespace

Sequence generate_sequence(const SequenceParams& params) {
    validate(params);
    Sequence s = best_of_attempts(make_problem(params), params);
    if (params.reuse) {
        // Reuse is allowed, not required: a schedule that delivers each read for its own
        // TripleMACs also runs on a machine that broadcasts, and may pack better.
        SequenceParams without = params;
        without.reuse = false;
        Sequence candidate = best_of_attempts(make_problem(without), without);
        if (candidate.cycles < s.cycles) s = std::move(candidate);
    }
    const Problem problem = make_problem(params);
    s.optimal_cycles = lower_bound(problem, params);
    s.reads_per_block = int(problem.needs.size());
    std::set<Point> points;
    for (const Need& n : problem.needs) points.insert(n.point);
    s.distinct_reads_per_block = int(points.size());
    return s;
}

std::string check_sequence(const Sequence& sequence, const SequenceParams& params) {
    // What each TripleMAC must receive: (point, coefficient, response), as a multiset.
    std::vector<std::multiset<std::tuple<int, int, int, int>>> wanted(params.triple_macs), got(params.triple_macs);
    for (int t = 0; t < kDeterminantsPerBlock; ++t) {
        const BlockDeterminant d = block_determinant(t);
        for (const Read& r : filter_reads(d.size))
            wanted[t].insert({d.px + r.dx, d.py + r.dy, r.coefficient, int(r.response)});
    }
    std::vector<int> busy_until(params.triple_macs, 0), last_cycle(params.triple_macs, -1);
    std::map<std::pair<int, int>, int> bus_use;  // (cycle, bus) -> count
    for (const Step& step : sequence.steps) {
        if (step.bus < 0 || step.bus >= int(params.read_buses)) return "a step uses bus " + std::to_string(step.bus);
        if (++bus_use[{step.cycle, step.bus}] > 1)
            return "bus " + std::to_string(step.bus) + " carries two words in cycle " + std::to_string(step.cycle);
        for (const Tap& tap : step.taps) {
            const std::string who = "TripleMAC " + std::to_string(tap.triple_mac) + " in cycle " + std::to_string(step.cycle);
            if (tap.triple_mac < 0 || tap.triple_mac >= int(params.triple_macs)) return "no " + who;
            if (last_cycle[tap.triple_mac] == step.cycle) return who + " takes two values";
            if (busy_until[tap.triple_mac] > step.cycle) return who + " is still busy with a x3";
            const int lx = params.bus_word == BusWord::quad ? tap.lane % 2 : 0;
            const int ly = params.bus_word == BusWord::quad ? tap.lane / 2 : 0;
            got[tap.triple_mac].insert({step.x + lx, step.y + ly, tap.coefficient, int(tap.response)});
            last_cycle[tap.triple_mac] = step.cycle;
            busy_until[tap.triple_mac] = step.cycle + (std::abs(tap.coefficient) == 3 ? int(params.x3_cycles) : 1);
            if (busy_until[tap.triple_mac] > sequence.cycles) return who + " is still adding when the sequence ends";
        }
    }
    for (unsigned t = 0; t < params.triple_macs; ++t)
        if (wanted[t] != got[t]) return "TripleMAC " + std::to_string(t) + " does not receive exactly its reads";
    return "";
}

}  // namespace surfvp::fhg
