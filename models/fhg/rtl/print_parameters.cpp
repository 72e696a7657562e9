// Writes fhg_params.vh (the path given) for the FHG model's defaults (Fhg::Params): the
// build verilates models/fhg/rtl with it (tests/CMakeLists.txt). `surfvp export-sequence`
// writes the same file for any configuration.
#include <cstdio>
#include <stdexcept>

#include "models/fhg/fhg.h"
#include "models/fhg/rtl_parameters.h"
#include "models/host/atomic_file.h"

// sc_main: the FHG's Params come with the SystemC model's library, whose main calls it.
int sc_main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTPUT.vh\n", argv[0]);
        return 2;
    }
    try {
        const surfvp::Fhg::Params defaults;
        surfvp::write_file_atomically(
            argv[1], surfvp::fhg::rtl_parameters(defaults.precision, defaults.sequence, defaults.max_width));
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
}
