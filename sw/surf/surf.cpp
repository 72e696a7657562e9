#include "sw/surf/surf.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <optional>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "models/host/disk_cache.h"
#include "sw/media/media.h"
#include "sw/surf/descriptor.h"
#include "sw/surf/fast_hessian.h"
#include "sw/surf/image_io.h"
#include "sw/surf/interpolation.h"
#include "sw/surf/local_maxima.h"
#include "sw/surf/orientation.h"
#include "sw/surf/parallel.h"
#include "sw/surf/twins.h"

namespace surfvp::surf {
namespace {

// Steps 1-2 on an integral image: refined maxima above `threshold`, with Laplacian sign, one
// per blob (twins.h) unless told otherwise.
Keypoints refined_maxima(const IntegralView& ii, const Params& params, float threshold, ResponseStack& stack) {
    const int threads = resolve_threads(params.threads);
    compute_responses(ii, params, threads, stack);
    Keypoints keypoints;
    for (const LocalMaximum& m : find_local_maxima(stack, threshold, threads)) {
        std::optional<Keypoint> kp = interpolate_maximum(stack, m, params.max_offset);
        if (!kp) continue;
        const ResponseOctave& oct = stack.octaves[static_cast<size_t>(m.octave)];
        kp->laplacian =
            hessian_at(ii, m.kx * oct.step, m.ky * oct.step, oct.layers[static_cast<size_t>(m.layer)].filter_size)
                .laplacian;
        keypoints.push_back(*kp);
    }
    if (params.one_per_blob) drop_twins(keypoints);
    return keypoints;
}

// Checks and the integral image, shared by the cv::Mat entry points.
IntegralView prepare(const cv::Mat& gray8, const Params& params, Workspace& workspace) {
    validate(params);
    check_image(gray8, params);
    workspace.integral.compute(gray8);
    return workspace.integral.view();
}

}  // namespace

void validate(const Params& params) {
    if (params.octaves < 1 || params.octaves > 4)
        throw std::invalid_argument(fmt::format("SURF octaves must be 1..4, got {}", params.octaves));
    if (params.intervals < 3 || params.intervals > 8)
        throw std::invalid_argument(fmt::format("SURF intervals must be 3..8, got {}", params.intervals));
    if (params.init_step != 1 && params.init_step != 2)
        throw std::invalid_argument(fmt::format("SURF init_step must be 1 or 2, got {}", params.init_step));
    if (params.threads < 0)
        throw std::invalid_argument(fmt::format("SURF threads must be >= 0, got {}", params.threads));
    if (params.haar != HaarMode::exact && params.haar != HaarMode::rounded)
        throw std::invalid_argument(fmt::format("SURF haar mode must be exact or rounded, got {}", int(params.haar)));
    if (params.descriptor != DescriptorKind::surf && params.descriptor != DescriptorKind::msurf)
        throw std::invalid_argument(
            fmt::format("SURF descriptor must be surf or msurf, got {}", int(params.descriptor)));
    if (!(params.max_offset > 0 && params.max_offset <= 2))
        throw std::invalid_argument(fmt::format("SURF max_offset must be in (0, 2], got {}", params.max_offset));
}

Keypoints detect(const IntegralView& ii, const Params& params) {
    validate(params);
    ResponseStack stack;
    return refined_maxima(ii, params, params.threshold, stack);
}

Keypoints detect(const cv::Mat& gray8, const Params& params, Workspace& workspace) {
    const IntegralView ii = prepare(gray8, params, workspace);
    return refined_maxima(ii, params, params.threshold, workspace.responses);
}

Keypoints detect(const cv::Mat& gray8, const Params& params) {
    Workspace workspace;
    return detect(gray8, params, workspace);
}

void describe(const IntegralView& ii, Keypoints& keypoints, const Params& params) {
    validate(params);
    parallel_for(static_cast<int>(keypoints.size()), resolve_threads(params.threads), [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
            Keypoint& kp = keypoints[static_cast<size_t>(i)];
            kp.orientation = params.upright ? 0.0f : orientation(ii, kp.x, kp.y, kp.scale, params.haar);
            kp.descriptor = descriptor(ii, kp, params.haar, params.descriptor);
        }
    });
}

void describe(const cv::Mat& gray8, Keypoints& keypoints, const Params& params) {
    Workspace workspace;
    describe(prepare(gray8, params, workspace), keypoints, params);
}

Keypoints detect_and_describe(const cv::Mat& gray8, const Params& params, Workspace& workspace) {
    const IntegralView ii = prepare(gray8, params, workspace);
    Keypoints keypoints = refined_maxima(ii, params, params.threshold, workspace.responses);
    describe(ii, keypoints, params);
    return keypoints;
}

Keypoints detect_and_describe(const cv::Mat& gray8, const Params& params) {
    Workspace workspace;
    return detect_and_describe(gray8, params, workspace);
}

std::vector<float> ranked_responses(const cv::Mat& gray8, Params params) {
    Workspace workspace;
    const IntegralView ii = prepare(gray8, params, workspace);
    std::vector<float> responses;
    for (const Keypoint& kp : refined_maxima(ii, params, 0.0f, workspace.responses)) responses.push_back(kp.response);
    std::sort(responses.begin(), responses.end(), std::greater<>());
    return responses;
}

std::vector<float> stored_ranked_responses(const cv::Mat& gray8, const Params& p) {
    const std::string key = fmt::format(
        "ranked v2 {} {} octaves {} intervals {} init_step {} max_offset {:a} one_per_blob {}", SURFVP_SURF_FINGERPRINT,
        media::content_key(gray8), p.octaves, p.intervals, p.init_step, double(p.max_offset), p.one_per_blob);
    if (const auto text = read_cached("ranked", key); text && text->size() % sizeof(float) == 0) {
        std::vector<float> responses(text->size() / sizeof(float));
        std::memcpy(responses.data(), text->data(), text->size());
        return responses;
    }
    std::vector<float> responses = ranked_responses(gray8, p);
    write_cached("ranked", key,
                 std::string(reinterpret_cast<const char*>(responses.data()), responses.size() * sizeof(float)));
    return responses;
}

float threshold_for_count(const cv::Mat& gray8, int target, Params params) {
    return threshold_for_rank(ranked_responses(gray8, params), target);
}

float threshold_for_rank(const std::vector<float>& responses, int target) {
    if (target <= 0) return responses.empty() ? 0.0f : responses.front();
    if (static_cast<size_t>(target) >= responses.size()) return 0.0f;
    const size_t t = static_cast<size_t>(target);
    const float halfway = 0.5f * (responses[t - 1] + responses[t]);
    return halfway < responses[t - 1] ? halfway : responses[t];  // adjacent floats: round down
}

}  // namespace surfvp::surf
