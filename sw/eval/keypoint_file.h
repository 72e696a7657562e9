#pragma once
// Keypoint files in the Mikolajczyk text format read by the standard evaluation code
// (vlbenchmarks readFeaturesFile, Oxford repeatability.m; docs/sources.md#evaluation):
//
//   line 1   descriptor dimension: 64, or 65 with the Laplacian sign first (0 or 1: none)
//   line 2   number of keypoints N
//   N lines  x y a b c [d1 .. dn]      a (x-u)^2 + 2 b (x-u)(y-v) + c (y-v)^2 = 1
//
// Keypoints are written as circles of radius r = 2.5 s (region.h): a = c = 1/r^2, b = 0. The
// scale, orientation and response the format cannot hold go to the sibling file NAME.meta
// (line 1: N; then "x y scale orientation response laplacian" per keypoint, same order), so a
// write/read round trip loses nothing. sw/eval/README.md documents both files.
#include <filesystem>

#include "sw/eval/format_error.h"
#include "sw/surf/keypoint.h"

namespace surfvp::eval {

struct KeypointFileOptions {
    bool laplacian = true;  // dimension 65, sign first (as Bay's SURF library with -lapl)
    bool meta = true;       // write NAME.meta; when false an existing NAME.meta is removed
};

struct KeypointFile {
    surf::Keypoints keypoints;
    unsigned dimension = 0;  // line 1 as read: 0 (no descriptors), 64 or 65
    bool meta_read = false;  // NAME.meta was found and supplied scale, orientation, response
};

// NAME.meta beside NAME.
std::filesystem::path meta_path(const std::filesystem::path& keypoint_file);

// Numbers are printed with %.9g, which round-trips every float exactly. Both files go through
// a temporary name and a rename. Throws std::runtime_error when the file cannot be written.
void write_keypoint_file(const std::filesystem::path& file, const surf::Keypoints& keypoints,
                         const KeypointFileOptions& options = {});

// Reads NAME and, when present, NAME.meta (which must list the same positions). Without the
// meta file the scale comes from the ellipse (the radius of the circle of equal area / 2.5),
// orientation and response are 0, and the Laplacian sign is the 65th column (0 when the
// dimension is 64). Throws FormatError naming file, line and problem on malformed input.
KeypointFile read_keypoint_file(const std::filesystem::path& file);

inline surf::Keypoints load_keypoints(const std::filesystem::path& file) { return read_keypoint_file(file).keypoints; }

}  // namespace surfvp::eval
