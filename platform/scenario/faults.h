#pragma once
// A scenario's `faults:` section (docs/faults.md): a list of faults to inject, each a map
//   - {kind: lost_interrupt, block: fhg, frame: 3}
//   - {kind: bus_error, master: iig, burst: 120}
// read with the file and line of each, and checked against the rest of the configuration
// before anything runs: a fault that cannot strike (a frame past the end, a block or master
// the workload does not use, a watchdog that is off) is bad input.
#include <string>
#include <vector>

#include "models/common/fault_plan.h"

namespace YAML {
class Node;
}

namespace surfvp {

class Config;

// Throws ConfigError naming the file, line and key.
std::vector<Fault> parse_faults(const std::string& path, const YAML::Node& list);
// `--set faults=[{kind: ..., ...}, ...]`: a list in flow YAML, in place of the scenario's
// (`faults=[]`: none); origin "--set".
std::vector<Fault> parse_faults_option(const std::string& value);
// Throws ConfigError for a fault that cannot strike in `config`.
void check_faults(const Config& config);
// The faults as the scenario YAML that gives them again (config.yaml).
std::string faults_yaml(const std::vector<Fault>& faults);

}  // namespace surfvp
