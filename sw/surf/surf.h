#pragma once
// The float reference SURF: the whole pipeline of the paper's §II on a CPU, as the golden
// model of the chip and its "CPU" column (Table II). Steps, each in its own file:
//   1. integral_image.h   integral image and box sums (eq. 1)
//   2. fast_hessian.h     box-filter Hessian determinants on octaves x intervals (eq. 3)
//      local_maxima.h     3x3x3 non-maximum suppression above the threshold
//      interpolation.h    sub-pixel / sub-scale refinement (eqs. 4-5)
//   3. orientation.h      dominant direction (optional: Params::upright)
//   4. descriptor.h       SURF-64 descriptor
// See README.md for parameters, units and limits.
#include <opencv2/core/mat.hpp>

#include "sw/surf/fast_hessian.h"
#include "sw/surf/integral_image.h"
#include "sw/surf/keypoint.h"
#include "sw/surf/params.h"

namespace surfvp::surf {

// Buffers that can live from one frame to the next: the integral image and the determinant
// planes (about 16 MB at 1024x768). Passing the same Workspace to successive calls saves their
// allocation and first-touch page faults; the calls without one use a temporary Workspace.
struct Workspace {
    IntegralImage integral;
    ResponseStack responses;
};

// Throws std::invalid_argument for parameters outside the supported ranges.
void validate(const Params& params);

// Interest points (steps 1-2): position, scale, response and Laplacian sign; orientation 0 and
// descriptor all zero; one per blob (twins.h: of two maxima within half a pixel and a scale
// ratio of 1.3 the stronger) unless params.one_per_blob is off. Order: octave, interval, row, column of the maximum.
// The cv::Mat form checks the image (ImageError) and builds the integral image.
Keypoints detect(const cv::Mat& gray8, const Params& params);
Keypoints detect(const cv::Mat& gray8, const Params& params, Workspace& workspace);
Keypoints detect(const IntegralView& ii, const Params& params);

// Orientation (0 when params.upright) and descriptor of each keypoint (steps 3-4), keypoints
// split over params.threads. Position, scale, response and Laplacian are left as they are.
void describe(const IntegralView& ii, Keypoints& keypoints, const Params& params);
void describe(const cv::Mat& gray8, Keypoints& keypoints, const Params& params);

// Steps 1-4.
Keypoints detect_and_describe(const cv::Mat& gray8, const Params& params);
Keypoints detect_and_describe(const cv::Mat& gray8, const Params& params, Workspace& workspace);

// The threshold for which detect(gray8, params) returns `target` keypoints, distinct blobs
// (fewer only if the image has fewer blobs with a positive determinant; then 0). Responses, maxima and the
// interpolation do not depend on the threshold, so they are computed once with threshold 0 and
// the threshold is placed halfway between the target-th and the next largest response:
// the count is exact unless responses tie there. params.threshold is ignored.
float threshold_for_count(const cv::Mat& gray8, int target, Params params);
// The same in two steps, for callers that try several targets on one image: the refined
// maxima's responses, largest first, and the threshold that keeps `target` of them.
std::vector<float> ranked_responses(const cv::Mat& gray8, Params params);
float threshold_for_rank(const std::vector<float>& ranked, int target);
// ranked_responses, kept across runs in the cache folder (models/host/disk_cache.h) under the
// image's content, the parameters detection depends on and a fingerprint of this library's
// source (taken by the build), so that a changed detector never reads old responses.
std::vector<float> stored_ranked_responses(const cv::Mat& gray8, const Params& params);

}  // namespace surfvp::surf
