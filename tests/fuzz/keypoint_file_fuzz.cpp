// Fuzz target: the keypoint-file reader (sw/eval/keypoint_file.h: read_keypoint_file), the
// Mikolajczyk text format and its NAME.meta sibling.
//
// Input: the keypoint file's text; when it holds a line "%%meta", the text after that line is
// the NAME.meta file (otherwise there is none).
//
// Expected answer to a malformed file: FormatError. Any other exception, a crash or a
// sanitizer report is a bug, and so is a file that reads but does not survive its own round
// trip: written back (write_keypoint_file, with its meta file) and read again, the keypoints
// are the same.
#include <cmath>
#include <string>

#include "fuzz_support.h"
#include "sw/eval/keypoint_file.h"

namespace {
using namespace surfvp;

// Equal as the file stores them (NaN cannot be read, so == is exact).
bool same(const surf::Keypoint& a, const surf::Keypoint& b) {
    return a.x == b.x && a.y == b.y && a.scale == b.scale && a.orientation == b.orientation &&
           a.response == b.response && a.laplacian == b.laplacian && a.descriptor == b.descriptor;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::string_view marker = "\n%%meta\n";
    const size_t split = text.find(marker);
    const std::filesystem::path file = fuzz::write_scratch("frame.surf", text.substr(0, split));
    if (split == std::string_view::npos)
        fuzz::remove_scratch("frame.surf.meta");
    else
        fuzz::write_scratch("frame.surf.meta", text.substr(split + marker.size()));
    try {
        const eval::KeypointFile read = eval::read_keypoint_file(file);
        const std::filesystem::path copy = fuzz::scratch_dir() / "copy.surf";
        eval::write_keypoint_file(copy, read.keypoints, {read.dimension == 65, true});
        const eval::KeypointFile again = eval::read_keypoint_file(copy);
        if (again.keypoints.size() != read.keypoints.size())
            fuzz::bug("the round trip changes the number of keypoints");
        for (size_t k = 0; k < read.keypoints.size(); ++k)
            if (!same(read.keypoints[k], again.keypoints[k]))
                fuzz::bug("the round trip changes keypoint " + std::to_string(k));
    } catch (const eval::FormatError&) {
        // the reader's answer to a malformed file
    } catch (const std::exception& e) {
        fuzz::unexpected(e);
    }
    return 0;
}
