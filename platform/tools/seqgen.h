#pragma once
// `surfvp seqgen`: the FHG's generated control sequence and what it implies, without a run.
#include <string>
#include <vector>

namespace surfvp {

struct SeqgenOptions {
    std::string scenario;  // optional: parameters start from this scenario
    std::vector<std::string> sets;
    unsigned width = 1024, height = 768;
};

// Prints one JSON object on stdout; throws ConfigError for bad input.
int seqgen_command(const SeqgenOptions& options);

}  // namespace surfvp
