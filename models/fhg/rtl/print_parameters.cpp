// Writes fhg_params.vh (the path given) for the model's default precision and machine: the
// build verilates models/fhg/rtl with it (tests/CMakeLists.txt). `surfvp export-sequence`
// writes the same file for any configuration.
#include <cstdio>
#include <stdexcept>

#include "models/fhg/rtl_parameters.h"
#include "models/host/atomic_file.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTPUT.vh\n", argv[0]);
        return 2;
    }
    try {
        surfvp::write_file_atomically(
            argv[1], surfvp::fhg::rtl_parameters(surfvp::fhg::Precision{}, surfvp::fhg::SequenceParams{}));
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
}
