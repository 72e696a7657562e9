// Writes fhg_params.vh (the first path given) for the FHG model's defaults (Fhg::Params): the
// build verilates models/fhg/rtl with it (models/CMakeLists.txt), and compiles the same text,
// as a C++ string literal (the second path), into rtl_datapath.cpp, which checks a
// configuration against it. `surfvp export-sequence` writes the file for any configuration.
// Fields given as NAME=VALUE after the paths change the defaults: precision widths, the line
// FIFO's organisation, the bus word and the bus count (the tests verilate a second machine,
// narrow enough to saturate, with a banked line FIFO and six pair buses).
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>

#include "models/fhg/fhg.h"
#include "models/fhg/rtl_parameters.h"
#include "models/host/atomic_file.h"

namespace {

// NAME=VALUE: a precision field's bits, or the machine's line_fifo, bus_word, read_buses or line_groups.
void set_field(surfvp::Fhg::Params& params, const std::string& assignment) {
    using surfvp::fhg::Precision;
    const std::map<std::string, unsigned Precision::*> bits{{"accumulator_bits", &Precision::accumulator_bits},
                                                            {"response_bits", &Precision::response_bits},
                                                            {"det_bits", &Precision::det_bits},
                                                            {"det_frac_bits", &Precision::det_frac_bits}};
    const std::map<std::string, surfvp::fhg::LineFifo> fifos{{"tdp", surfvp::fhg::LineFifo::tdp},
                                                             {"tdp_x2", surfvp::fhg::LineFifo::tdp_x2},
                                                             {"banked", surfvp::fhg::LineFifo::banked},
                                                             {"sdp72", surfvp::fhg::LineFifo::sdp72}};
    const std::map<std::string, surfvp::fhg::BusWord> words{{"scalar", surfvp::fhg::BusWord::scalar},
                                                            {"pair", surfvp::fhg::BusWord::pair},
                                                            {"quad", surfvp::fhg::BusWord::quad}};
    const size_t eq = assignment.find('=');
    const std::string name = assignment.substr(0, eq), value = eq == std::string::npos ? "" : assignment.substr(eq + 1);
    if (bits.count(name))
        params.precision.*(bits.at(name)) = unsigned(std::stoul(value));
    else if (name == "line_fifo" && fifos.count(value))
        params.sequence.line_fifo = fifos.at(value);
    else if (name == "bus_word" && words.count(value))
        params.sequence.bus_word = words.at(value);
    else if (name == "read_buses")
        params.sequence.read_buses = unsigned(std::stoul(value));
    else if (name == "line_groups")
        params.sequence.line_groups = unsigned(std::stoul(value));
    else
        throw std::invalid_argument(
            "not a precision field NAME=BITS or line_fifo, bus_word, read_buses, line_groups: " + assignment);
}

}  // namespace

// sc_main: the FHG's Params come with the SystemC model's library, whose main calls it.
int sc_main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s OUTPUT.vh OUTPUT.inc [FIELD=VALUE]...\n", argv[0]);
        return 2;
    }
    try {
        surfvp::Fhg::Params params;
        for (int i = 3; i < argc; ++i) set_field(params, argv[i]);
        const std::string text = surfvp::fhg::rtl_parameters(params.precision, params.sequence, params.max_width);
        surfvp::write_file_atomically(argv[1], text);
        surfvp::write_file_atomically(argv[2], "R\"vh(" + text + ")vh\"\n");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
}
