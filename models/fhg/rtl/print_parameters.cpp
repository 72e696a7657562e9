// Writes fhg_params.vh (the first path given) for the FHG model's defaults (Fhg::Params): the
// build verilates models/fhg/rtl with it (models/CMakeLists.txt), and compiles the same text,
// as a C++ string literal (the second path), into rtl_datapath.cpp, which checks a
// configuration against it. `surfvp export-sequence` writes the file for any configuration.
#include <cstdio>
#include <stdexcept>

#include "models/fhg/fhg.h"
#include "models/fhg/rtl_parameters.h"
#include "models/host/atomic_file.h"

// sc_main: the FHG's Params come with the SystemC model's library, whose main calls it.
int sc_main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s OUTPUT.vh OUTPUT.inc\n", argv[0]);
        return 2;
    }
    try {
        const surfvp::Fhg::Params defaults;
        const std::string text = surfvp::fhg::rtl_parameters(defaults.precision, defaults.sequence, defaults.max_width);
        surfvp::write_file_atomically(argv[1], text);
        surfvp::write_file_atomically(argv[2], "R\"vh(" + text + ")vh\"\n");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
}
