#pragma once
// Whether a configuration closes its clocks: each clock domain's frequency against the highest
// the device can run it at (docs/resources.md, "Clock closure"). A domain above its maximum is
// a chip that could not have been built, a missed goal of the run, never a refusal: the
// simulated figures are still those of the configuration as given. Plain C++ on the
// configuration.
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "platform/scenario/config.h"

namespace surfvp {

struct ClockDomain {
    std::string name;   // "FHG line FIFO block RAM"
    double clock_hz;    // what the configuration clocks it at
    double fmax_hz;     // the highest the device runs it at
    std::string basis;  // how both were reached, with the parameters that set them
    bool closes() const { return clock_hz <= fmax_hz; }
};

struct ClockClosure {
    std::vector<ClockDomain> domains;
    std::vector<std::string> failing;  // "FHG line FIFO block RAM: 500 MHz, above its 450 MHz (...)"
    bool closes() const { return failing.empty(); }
};

ClockClosure clock_closure(const Config& config);
nlohmann::ordered_json closure_json(const ClockClosure& closure);

}  // namespace surfvp
