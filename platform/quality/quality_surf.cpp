// `surfvp surf`: the float reference SURF on one image, written as a keypoint file; and the
// SURF run that `eval-seq` repeats on every frame.
#include <chrono>
#include <cstdio>

#include "platform/quality/quality_tasks.h"
#include "platform/run/run.h"
#include "sw/eval/keypoint_file.h"
#include "sw/surf/image_io.h"
#include "sw/surf/surf.h"

namespace surfvp::quality {

surf::Params SurfSettings::params() const {
    surf::Params p = paper ? surf::paper_surf() : surf::Params{};
    if (intervals) p.intervals = *intervals;
    if (descriptor) p.descriptor = *descriptor == "surf" ? surf::DescriptorKind::surf : surf::DescriptorKind::msurf;
    if (max_offset) p.max_offset = *max_offset;
    if (threshold) p.threshold = *threshold;
    p.upright = upright;
    p.octaves = octaves;
    p.init_step = init_step;
    p.haar = haar == "rounded" ? surf::HaarMode::rounded : surf::HaarMode::exact;
    p.threads = threads;
    return p;
}

Detection detect(const cv::Mat& gray, const SurfSettings& settings, const std::string& name) {
    surf::Params params = settings.params();
    // check_image's message starts with `name` already.
    read_input("", [&] {
        surf::validate(params);
        surf::check_image(gray, params, name);
    });
    const auto start = std::chrono::steady_clock::now();
    Detection detection;
    if (settings.target_count) {
        const std::vector<float> ranked = surf::ranked_responses(gray, params);
        params.threshold = surf::threshold_for_rank(ranked, *settings.target_count);
        detection.blobs = ranked.size();
    }
    detection.keypoints = surf::detect_and_describe(gray, params);
    detection.threshold = params.threshold;
    detection.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return detection;
}

int run_surf(const SurfCommand& command) {
    const cv::Mat gray = read_input("", [&] { return surf::load_gray(command.image, command.surf.params()); });
    const Detection detection = detect(gray, command.surf, command.image);
    eval::KeypointFileOptions options;
    options.laplacian = !command.no_laplacian;
    read_input("--out", [&] { eval::write_keypoint_file(command.out, detection.keypoints, options); });
    if (command.quiet) return kExitOk;
    std::fprintf(stderr, "%zu keypoints, threshold %.9g, %.1f ms\n", detection.keypoints.size(),
                 static_cast<double>(detection.threshold), detection.milliseconds);
    // Fewer keypoints than asked: say why rather than let the count look like a bug. An image
    // with fewer blobs gives them all (threshold 0); blobs whose responses tie at the target's
    // rank are kept or dropped together.
    const auto target = command.surf.target_count;
    if (target && detection.keypoints.size() < static_cast<std::size_t>(*target)) {
        if (detection.blobs < static_cast<std::size_t>(*target))
            std::fprintf(stderr,
                         "surfvp: note: %s has only %zu blobs with a positive response, one keypoint each "
                         "(--target-count %d)\n",
                         command.image.c_str(), detection.blobs, *target);
        else
            std::fprintf(stderr,
                         "surfvp: note: %s: %zu keypoints, not %d: blobs tie in response at rank %d, and a threshold "
                         "keeps all or none of them\n",
                         command.image.c_str(), detection.keypoints.size(), *target, *target);
    }
    return kExitOk;
}

}  // namespace surfvp::quality
