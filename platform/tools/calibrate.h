#pragma once
// `surfvp calibrate`: the software stage's prices from its real PPC440 instruction stream.
// For each Haar mode, a VP run of the fitting scenario records what the stage saw (buffers,
// FIFO words, results); the stage cross-compiled for the PPC440 (sw/cpu_cost/firmware) runs
// on that input under qemu-ppc; its keypoints must equal the VP's; its instruction stream,
// timed by the pipeline model under every probe, is fitted per unit of work into the table
// the native model prices from (sw/cpu_cost/calibration.json). Each check scenario is run the
// same way and the table's prices are compared with its stream, per step and in total.
#include <string>
#include <vector>

namespace surfvp {

struct CalibrateOptions {
    // The table is fitted on the fit scenarios' candidates together (their data differ: a flat
    // patch skips an angle, a textured one does not), then checked on each scenario.
    std::vector<std::string> fit{"budget_1024x768", "castle_sequence"};
    std::vector<std::string> check{"graf"};
    // A scenario run once more with M-SURF descriptors (surf.descriptor=msurf) and fitted with
    // the rest, for the msurf unit's price; "none": not priced (its price is then 0).
    std::string msurf = "budget_1024x768";
    std::vector<std::string> sets;  // for every run
    int frames = 2;                 // per scenario
    std::string out = "traces/calibration";
    std::string table;   // also write the fitted table here (sw/cpu_cost/calibration.json)
    bool probes = true;  // time the stream under every knob's probes and the check points too
    bool quiet = false;
    std::string firmware;  // default: the build's
};

int calibrate_command(const CalibrateOptions& options);

}  // namespace surfvp
