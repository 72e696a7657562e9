#pragma once
// Detector repeatability under a known homography (Mikolajczyk et al., IJCV 2005 §4.1, as
// vlbenchmarks' RepeatabilityBenchmark computes it; docs/sources.md#evaluation), and the precision of
// descriptor matching under the same homography.
#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/types.hpp>

#include "sw/eval/ellipse.h"
#include "sw/eval/matching.h"
#include "sw/surf/keypoint.h"

namespace surfvp::eval {

struct RepeatabilityOptions {
    double max_overlap_error = 0.4;  // IJCV 2005 §4.1; vlbenchmarks' OverlapError default
    double normalised_radius = 30;   // px: region A rescaled to this circle's area
    int overlap_rows = 2048;         // ellipse_overlap's integration rows
};

struct RegionMatch {
    std::size_t a = 0, b = 0;  // indices into the input keypoint sets
    double overlap_error = 0;  // 1 - |A n B| / |A u B| after normalisation
};

struct RepeatabilityResult {
    std::size_t visible_a = 0;         // regions of A fully inside image A and, mapped, image B
    std::size_t visible_b = 0;         // regions of B fully inside image B and, mapped back, A
    std::size_t correspondences = 0;   // visible pairs with overlap error below the maximum
    std::vector<RegionMatch> matches;  // one-to-one, chosen greedily by increasing overlap error
    double repeatability = 0;          // matches / min(visible_a, visible_b); 0 if that is 0
};

// A keypoint's region: the circle of radius 2.5 s (region.h).
Ellipse keypoint_region(const surf::Keypoint& k);

// vlbenchmarks' isEllipseInBBox in 0-based pixels: the bounding box lies strictly inside
// (0, width) x (0, height).
bool region_visible(const Ellipse& region, const cv::Size& image);

// The overlap error of region `a` and region `b` (both in A's image): both shapes are scaled
// about their own centres by the factor that gives `a` the area of a circle of radius
// `normalised_radius`; the centres do not move (vlbenchmarks fastEllipseOverlap), so the offset
// between them stays in pixels.
double overlap_error(const Ellipse& a, const Ellipse& b, double normalised_radius = 30, int rows = 2048);

// Repeatability of A (image of size `size_a`) and B (size `size_b`); `h_ab` maps A's pixels to
// B's. Overlaps are measured in A's image, B's regions mapped through h_ab^-1.
RepeatabilityResult repeatability(const surf::Keypoints& a, const surf::Keypoints& b, const Eigen::Matrix3d& h_ab,
                                  const cv::Size& size_a, const cv::Size& size_b,
                                  const RepeatabilityOptions& options = {});

struct PrecisionResult {
    std::size_t candidates = 0;  // ratio-test candidates (matching.h)
    std::size_t correct = 0;     // h_ab maps A's point within the tolerance of B's
    double precision = 0;        // correct / candidates; 0 without candidates
    std::vector<Candidate> candidate_pairs;
    std::vector<double> errors;  // px, |h_ab(x_a) - x_b| per candidate
};

// Matching precision under a homography: of the ratio-test candidates, the share whose point in
// B is within `tolerance` px (inclusive) of A's point mapped by h_ab. All keypoints take part,
// visible or not.
PrecisionResult matching_precision(const surf::Keypoints& a, const surf::Keypoints& b, const Eigen::Matrix3d& h_ab,
                                   const RatioTestOptions& matching = {}, double tolerance = 3.0);

}  // namespace surfvp::eval
