#pragma once
// `surfvp export-sequence`: the FHG's configured control sequence as the MasterController's
// block RAM holds it (models/fhg/sequence_memory.h), for RTL; and `--check`, which reads such
// an image back and replays it against the configured machine.
#include <string>
#include <vector>

namespace surfvp {

struct ExportSequenceOptions {
    std::string scenario;  // optional: parameters start from this scenario
    std::vector<std::string> sets;
    std::string out = "traces/sequence";
    std::string check;  // an image (.coe or .mem) to decode and replay instead of writing one
};

// Writes fhg_sequence.coe, fhg_sequence.mem, fhg_sequence.json and the RTL's fhg_params.vh
// (models/fhg/rtl) for the configuration into the folder and prints
// the summary; with --check prints what the replay found. Throws ConfigError for bad input
// (an image the configuration's layout cannot read or whose sequence breaks a limit).
int export_sequence_command(const ExportSequenceOptions& options);

}  // namespace surfvp
