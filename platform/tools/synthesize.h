#pragma once
// `surfvp synthesize`: the FHG datapath's Verilog reference (models/fhg/rtl) with the
// configuration's parameters and sequence image, synthesized part by part by yosys for the
// device's FPGA family, beside the resource model's estimate of each part
// (platform/cost/fpga_resources.h, FhgParts). docs/rtl.md.
#include <string>
#include <vector>

namespace surfvp {

struct SynthesizeOptions {
    std::string scenario;  // optional: parameters start from this scenario
    std::vector<std::string> sets;
    std::string out = "traces/synthesis";
    std::string family;       // yosys synth_xilinx -family; empty: fpga.device's
    bool whole_fifo = false;  // also the whole line FIFO: its BRAMs and the routing (minutes)
};

// Writes rtl/ (the Verilog, fhg_params.vh, fhg_sequence.mem), yosys/ (each part's log and
// statistics), synthesis.md and synthesis.json into the folder and prints the table. Throws
// ConfigError when yosys is missing, the family is unknown or the RTL cannot build the
// configuration; std::runtime_error with the log's last error when yosys fails.
int synthesize_command(const SynthesizeOptions& options);

}  // namespace surfvp
