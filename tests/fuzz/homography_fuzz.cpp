// Fuzz target: the homography reader (sw/eval/homography.h: read_homography_file), both of its
// formats: Oxford plain text (three lines of three numbers, as H1to2p) and an OpenCV
// FileStorage file (XML, YAML or JSON, as opencv-doc's H1to3p.xml; the reader tells them apart
// by their first characters, OpenCV by its own means).
//
// Input: the file's bytes.
//
// Expected answer to a malformed file: FormatError. Any other exception, a crash or a
// sanitizer report is a bug, and so is a matrix the reader returns although it promised to
// refuse it: one with a non-finite element.
#include <string>

#include "fuzz_support.h"
#include "sw/eval/homography.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace surfvp;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::filesystem::path file = fuzz::write_scratch("H1toNp", bytes);
    try {
        const Eigen::Matrix3d h = eval::read_homography_file(file);
        if (!h.allFinite()) fuzz::bug("the reader returned a non-finite homography");
    } catch (const eval::FormatError&) {
        // the reader's answer to a malformed file
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
