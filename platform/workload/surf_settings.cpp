// SurfWorkloadSettings' and EvalSettings' scenario parameters, each bound to the field it sets.
#include "platform/workload/surf_settings.h"

namespace surfvp {

using unit::s;

const ParamTable<SurfWorkloadSettings>& SurfWorkloadSettings::parameter_table() {
    using P = SurfWorkloadSettings;
    static const ParamTable<P> table(
        {field<P>({"surf.source",
                   ParamKind::text,
                   "/usr/share/doc/opencv-doc/examples/data/graf1.png",
                   0,
                   0,
                   {},
                   "Frames: an image (repeated), a folder of images, a list file or a video",
                   "[-] Debian opencv-doc's graf1"},
                  &P::source),
         field<P>({"surf.frames", ParamKind::count, "20", 1, 100000, {}, "Frames to process", "[-] scenario size"},
                  &P::frames),
         field<P>({"surf.width",
                   ParamKind::count,
                   "1024",
                   0,
                   4096,
                   {},
                   "Frames are resized to this width (0: as they are)",
                   "[S] paper: 1024 x 768 frames"},
                  &P::width),
         field<P>({"surf.height",
                   ParamKind::count,
                   "768",
                   0,
                   4096,
                   {},
                   "Frames are resized to this height (0: as they are)",
                   "[S] paper: 1024 x 768 frames"},
                  &P::height),
         field<P>({"surf.target_keypoints",
                   ParamKind::count,
                   "100",
                   0,
                   100000,
                   {},
                   "Calibrate the threshold on the first frame (float reference) to give about this many keypoints; 0: "
                   "use surf.threshold",
                   "[S] paper: ~100 descriptors per image"},
                  &P::target_keypoints),
         field<P>({"surf.threshold",
                   ParamKind::real,
                   "500",
                   0,
                   1e9,
                   {},
                   "Determinant threshold (units of sw/surf/README.md) when not calibrated",
                   "[A] a middle value for 1024x768 scenes"},
                  &P::threshold),
         choice<P, bool>(
             {"surf.threshold_control",
              ParamKind::choice,
              "hold",
              0,
              0,
              {},
              "hold: the calibrated threshold for every frame; track: each frame's threshold from the keypoint count "
              "of the frame surf.tasks_in_flight before it, aiming at surf.target_keypoints",
              "[-] a software setting: hold is the paper's one THRESHOLD register, track what a camera pipeline does"},
             &P::track, {{"hold", false}, {"track", true}}),
         field<P>({"surf.upright",
                   ParamKind::choice,
                   "off",
                   0,
                   0,
                   {"on", "off"},
                   "Skip the orientation (U-SURF)",
                   "[S] paper §II: orientation is optional"},
                  &P::upright),
         choice<P, surf::HaarMode>(
             {"surf.haar",
              ParamKind::choice,
              "rounded",
              0,
              0,
              {},
              "The CPU's Haar wavelets: at whole pixels with integer sizes (6 reads each), or exact at sub-pixel "
              "positions like the float reference",
              "[A] embedded SURF of the time (OpenSURF) samples at whole pixels; what each costs the CPU is a run's "
              "software_time_per_keypoint_us (verdict.software runs both; docs/sources.md#surf)"},
             &P::haar, {{"rounded", surf::HaarMode::rounded}, {"exact", surf::HaarMode::exact}}),
         field<P>(
             {"surf.max_offset",
              ParamKind::real,
              "0.5",
              0.5,
              2,
              {},
              "The CPU's interpolation drops a local maximum whose fitted offset exceeds this, in samples, in x, y "
              "or scale (1 keeps the maxima that lie between two samples)",
              "[S] paper §II: 0.5; OpenCV's SURF keeps up to 1, which the float reference uses (docs/quality.md)"},
             &P::max_offset),
         choice<P, surf::DescriptorKind>(
             {"surf.descriptor",
              ParamKind::choice,
              "surf",
              0,
              0,
              {},
              "The CPU's descriptor: surf, Bay's 4 x 4 sub-regions of 5 x 5 samples under one Gaussian; msurf, "
              "M-SURF's overlapping 9 x 9-sample sub-regions, each under its own Gaussian and weighted by a second",
              "[S] paper §II: Bay et al.'s descriptor; M-SURF (Agrawal et al., ECCV 2008) is OpenSURF's default, "
              "priced by the calibration as its own unit of work (sw/cpu_cost/calibration.md)"},
             &P::descriptor, {{"surf", surf::DescriptorKind::surf}, {"msurf", surf::DescriptorKind::msurf}}),
         field<P>({"surf.tasks_in_flight",
                   ParamKind::count,
                   "2",
                   1,
                   16,
                   {},
                   "Tasks between hardware start and descriptors done (buffer sets in memory: a frame, its integral "
                   "image, determinants and descriptors; a frame arrives in its set as its task starts)",
                   "[S] paper §III-D: tasks overlap; two let the CPU describe one while the hardware does the next"},
                  &P::tasks_in_flight),
         field<P>({"surf.fifo_irq_level",
                   ParamKind::count,
                   "256",
                   1,
                   1 << 20,
                   {},
                   "Maxima FIFO level that interrupts the CPU to drain it",
                   "[A] a quarter of the default FIFO"},
                  &P::fifo_irq_level),
         field<P>({"surf.watchdog",
                   ParamKind::duration,
                   "0 s",
                   0,
                   3600 * s,
                   {},
                   "libSSA2's watchdog: a task's hardware still unfinished this long after its start is checked "
                   "(a block found finished lost its interrupt; one still BUSY fails the task); 0: off",
                   "[-] off unless a scenario arms it (scenarios/faults.yaml: 100 ms): an armed timeout moves one PLB2 "
                   "burst in 10^5 by a wait bin between DMA granularities (an open kernel-ordering sensitivity)"},
                  &P::watchdog),
         field<P>(
             {"surf.spurious_irq_limit",
              ParamKind::count,
              "64",
              0,
              1 << 20,
              {},
              "Interrupts in a row from one line with nothing to serve that make libSSA2 call the line stuck "
              "(fail the task, reset the pair); 0: never",
              "[-] driver setting (no fault-free figure depends on it): a line that has just let go can give one; in "
              "scenarios/faults.yaml all 64 came from the stuck line"},
             &P::spurious_irq_limit),
         field<P>({"budget.fps",
                   ParamKind::real,
                   "10",
                   0,
                   1e6,
                   {},
                   "Frames per second the scenario must sustain (0: no budget)",
                   "[S] paper: ~10 FPS at 1024 x 768"},
                  &P::budget_fps)});
    return table;
}

const ParamTable<EvalSettings>& EvalSettings::parameter_table() {
    using P = EvalSettings;
    static const ParamTable<P> table(
        {field<P>({"eval.homography",
                   ParamKind::text,
                   "",
                   0,
                   0,
                   {},
                   "Homography from frame 0 to frame 1 (Oxford or OpenCV file): report repeatability and precision",
                   "[-] evaluation"},
                  &P::homography),
         field<P>({"eval.poses",
                   ParamKind::text,
                   "",
                   0,
                   0,
                   {},
                   "Folder of Camera_NNN.txt poses (ViSP castle): report distinguishability with the true F too",
                   "[-] evaluation"},
                  &P::poses),
         field<P>({"eval.gap",
                   ParamKind::count,
                   "2",
                   1,
                   1000,
                   {},
                   "Pairs (i, i + gap) evaluated besides consecutive frames (camera poses, surfvp table2)",
                   "[-] evaluation"},
                  &P::gap)});
    return table;
}

SurfWorkloadSettings surf_settings(const ParamValues& values) {
    return SurfWorkloadSettings::parameter_table().make(values);
}
EvalSettings eval_settings(const ParamValues& values) { return EvalSettings::parameter_table().make(values); }

}  // namespace surfvp
