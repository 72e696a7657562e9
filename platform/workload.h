#pragma once
// What the CPU runs in a scenario, and what the run is judged on. Each workload builds its
// software (against the HAL only), says how far it has come, and lists its checks.
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config.h"
#include "models/ppc440/ppc440.h"

namespace surfvp {

struct Check {
    std::string name;
    bool passed;
    std::string detail;
};

struct Progress {
    uint64_t done = 0;
    uint64_t total = 0;
    std::string unit;  // "copies", "frames"
};

class Workload {
public:
    virtual ~Workload() = default;
    virtual Ppc440::Software software() = 0;
    virtual Progress progress() const = 0;
    virtual std::vector<Check> checks() const = 0;
    virtual nlohmann::ordered_json report() const = 0;  // the workload's own section
};

// The workload `run.workload` names; throws ConfigError when its parameters do not fit the
// platform (a buffer outside memory, say).
std::unique_ptr<Workload> make_workload(const Config& config);

}  // namespace surfvp
