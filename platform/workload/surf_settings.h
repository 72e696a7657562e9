#pragma once
// The SURF workload's settings: the frames (source, count, size), the software the CPU runs
// on them (libSSA2's threshold, tasks in flight and interrupt level; SURF's orientation, Haar
// wavelets, interpolation limit and descriptor), the frame budget, and what the evaluation compares the
// keypoints with. The workload, the verdict and Table II read them through these structs.
#include <cstdint>
#include <string>

#include "models/common/parameter.h"
#include "sw/surf/params.h"

namespace surfvp {

struct SurfWorkloadSettings {
    std::string source;                             // surf.source: an image, a folder, a list file or a video
    uint64_t frames = 0;                            // surf.frames
    unsigned width = 0, height = 0;                 // surf.width, surf.height (0: as the source is)
    uint64_t target_keypoints = 0;                  // surf.target_keypoints (0: surf.threshold)
    double threshold = 0;                           // surf.threshold
    bool track = false;                             // surf.threshold_control: track rather than hold
    bool upright = false;                           // surf.upright
    surf::HaarMode haar = surf::HaarMode::rounded;  // surf.haar
    float max_offset = 0.5f;                        // surf.max_offset
    surf::DescriptorKind descriptor = surf::DescriptorKind::surf;  // surf.descriptor
    unsigned tasks_in_flight = 2;                                  // surf.tasks_in_flight
    uint32_t fifo_irq_level = 0;                                   // surf.fifo_irq_level
    Duration watchdog;                                             // surf.watchdog (0: off)
    unsigned spurious_irq_limit = 0;                               // surf.spurious_irq_limit
    double budget_fps = 0;                                         // budget.fps (0: no budget)

    static const ParamTable<SurfWorkloadSettings>& parameter_table();
};
SurfWorkloadSettings surf_settings(const ParamValues& values);

// What the keypoints are evaluated against: a homography from frame 0 to frame 1, a folder of
// camera poses, and the gap of the pairs besides consecutive frames.
struct EvalSettings {
    std::string homography;  // eval.homography ("" : none)
    std::string poses;       // eval.poses ("" : none)
    uint64_t gap = 2;        // eval.gap

    static const ParamTable<EvalSettings>& parameter_table();
};
EvalSettings eval_settings(const ParamValues& values);

}  // namespace surfvp
