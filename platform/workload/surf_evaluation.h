#pragma once
// Feature quality on the chip's own keypoints, where the scenario gives the geometry: a
// homography from frame 0 to frame 1 (eval.homography: repeatability and matching precision)
// or each frame's camera pose (eval.poses: distinguishability over frame pairs).
#include <nlohmann/json.hpp>
#include <vector>

#include "platform/workload/frame_source.h"
#include "sw/surf/surf.h"

namespace surfvp {

// The geometry read and checked against the frames before anything is built: a homography at
// the frames' own size, poses that belong to the very frames the source gives, one each, with
// two distinct camera centres in every pair. Throws ConfigError naming the key's origin.
void check_eval_inputs(const Config& c, const SourceFrames& frames);

// Whether the evaluation needs frame `frame`'s keypoints: frames 0 and 1 under a homography,
// every frame under poses (the others' live in their keypoint files only).
bool evaluation_needs(const Config& config, size_t frame);

// The figures, from every frame's keypoints (those evaluation_needs); an empty object when the
// scenario gives no geometry.
nlohmann::ordered_json evaluate(const Config& config, const SourceFrames& source,
                                const std::vector<const surf::Keypoints*>& keypoints);

}  // namespace surfvp
