#pragma once
// The chain of limits (docs/architecture.md#principles, 7): the verdict names what limits the frame rate, finds
// its break-even (the value of a parameter of the limit's cause that just meets the budget, by
// re-simulation, then checked by a run of the whole scenario), re-simulates with the limit
// relieved at that value and names the next limit with its headroom, up to `depth` limits.
// - A busy block's axes are its own clock (and the FHG's cycles per block); a CPU that spends
//   a tenth of its time or more stalled on line fills also gets the memory latency and the
//   clock of its path to DDR; a buffer coupling its depth; a wait the clock of what it waits on.
// - Each search bisects to 0.1 % of a clock (one step of a count) on the re-simulations' frame
//   count; when the whole-run check misses, the value moves one tolerance further and is
//   checked again, so the value reported passes its own check.
// - Once a limit is relieved at its break-even it runs at the budget, so the next limit is the
//   one the run names if it is another resource, otherwise the resource with the least
//   headroom (the lowest frame rate it alone would allow) among those not yet relieved. The
//   last limit of the chain is named with its headroom; its break-even is not searched (nothing
//   would be relieved after it).
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "platform/scenario/config.h"
#include "platform/run/resimulation.h"

namespace surfvp {

// A re-simulation's configuration: `base` with `sets` applied, their origin "verdict".
Config verdict_variant(const Config& base, const std::vector<std::pair<std::string, std::string>>& sets);

class LimitChain {
public:
    // `config` is the scenario (its whole-run checks), `reference` the re-simulations' version.
    LimitChain(const Config& config, const Config& reference, double budget, Resimulation& pool, size_t depth);
    ~LimitChain();

    // Starts from the reference's result (its limit); submits what it needs to `pool`.
    void start(const nlohmann::ordered_json& reference_point);

    // About how many re-simulations a chain of `depth` limits takes, for a progress line's
    // total only: every step but the last searches its limit's break-even on about two axes in
    // about six runs each, then checks it and re-simulates the relieved scenario (the default
    // scenario's chain took 29).
    static size_t expected_runs(size_t depth) { return depth > 1 ? (depth - 1) * 15 : 0; }

    // The steps: each limit, its headroom, what was relieved to reach it, its searches.
    nlohmann::ordered_json json() const;

private:
    struct Step;
    void begin(size_t k, const nlohmann::ordered_json& point);
    void drive(size_t k, size_t i);
    void check(size_t k, size_t i, double value);
    void done(size_t k);

    const Config& config_;
    const Config& reference_;
    double budget_;
    Resimulation& pool_;
    size_t depth_;
    std::vector<std::unique_ptr<Step>> steps_;
};

}  // namespace surfvp
