// Writes fhg_params.vh (the first path given) for the FHG model's defaults (Fhg::Params): the
// build verilates models/fhg/rtl with it (models/CMakeLists.txt), and compiles the same text,
// as a C++ string literal (the second path), into rtl_datapath.cpp, which checks a
// configuration against it. `surfvp export-sequence` writes the file for any configuration.
// Precision fields given as NAME=BITS after the paths change the defaults (the tests verilate
// a narrow datapath whose responses and determinants saturate).
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>

#include "models/fhg/fhg.h"
#include "models/fhg/rtl_parameters.h"
#include "models/host/atomic_file.h"

namespace {

void set_precision(surfvp::fhg::Precision& p, const std::string& assignment) {
    const std::map<std::string, unsigned surfvp::fhg::Precision::*> fields{
        {"accumulator_bits", &surfvp::fhg::Precision::accumulator_bits},
        {"response_bits", &surfvp::fhg::Precision::response_bits},
        {"det_bits", &surfvp::fhg::Precision::det_bits},
        {"det_frac_bits", &surfvp::fhg::Precision::det_frac_bits}};
    const size_t eq = assignment.find('=');
    const auto field = fields.find(assignment.substr(0, eq));
    if (eq == std::string::npos || field == fields.end())
        throw std::invalid_argument("not a precision field NAME=BITS: " + assignment);
    p.*(field->second) = unsigned(std::stoul(assignment.substr(eq + 1)));
}

}  // namespace

// sc_main: the FHG's Params come with the SystemC model's library, whose main calls it.
int sc_main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s OUTPUT.vh OUTPUT.inc [PRECISION_FIELD=BITS]...\n", argv[0]);
        return 2;
    }
    try {
        surfvp::Fhg::Params params;
        for (int i = 3; i < argc; ++i) set_precision(params.precision, argv[i]);
        const std::string text = surfvp::fhg::rtl_parameters(params.precision, params.sequence, params.max_width);
        surfvp::write_file_atomically(argv[1], text);
        surfvp::write_file_atomically(argv[2], "R\"vh(" + text + ")vh\"\n");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
}
