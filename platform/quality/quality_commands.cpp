// CLI11 registration of `surfvp surf`, `eval`, `eval-seq` and `draw`; the bodies are in
// quality_surf.cpp, quality_eval.cpp, quality_sequence.cpp and quality_draw.cpp.
#include "platform/quality/quality_commands.h"

#include "platform/quality/quality_tasks.h"

namespace surfvp {
namespace {

using namespace quality;

constexpr const char* kDocs = "Metrics and examples: docs/quality.md; definitions: sw/eval/README.md.\n";

// The detector options `surf` and `eval-seq` share. Optional values are set from callbacks so
// that "not given" stays distinguishable from any value.
void add_surf_options(CLI::App& command, SurfSettings& surf) {
    CLI::Option* threshold = command.add_option_function<float>(
        "--threshold", [&surf](const float& t) { surf.threshold = t; },
        "Hessian determinant threshold (sw/surf/README.md units; default 26 = OpenSURF's 0.0004; "
        "OpenCV's hessianThreshold is ~20-25x larger for the same points)");
    threshold->check(CLI::NonNegativeNumber);
    CLI::Option* count = command.add_option_function<int>(
        "--target-count", [&surf](const int& n) { surf.target_count = n; },
        "Per image, the threshold that gives exactly N keypoints (fewer only if the image has fewer)");
    count->check(CLI::PositiveNumber);
    threshold->excludes(count);
    command.add_flag("--upright", surf.upright, "U-SURF: no orientation assignment (orientation 0)");
    command.add_option("--octaves", surf.octaves, "Octaves, 1..4")->check(CLI::Range(1, 4))->capture_default_str();
    command.add_option("--init-step", surf.init_step, "Sampling step of octave 0: 1 (the chip) or 2 (OpenSURF)")
        ->check(CLI::Range(1, 2))
        ->capture_default_str();
    command
        .add_option("--haar", surf.haar,
                    "Haar wavelets of orientation and descriptor: exact (sub-pixel, the float reference) or rounded "
                    "(whole pixels, the chip's software: surf.haar)")
        ->check(CLI::IsMember({"exact", "rounded"}))
        ->capture_default_str();
    command.add_flag(
        "--paper", surf.paper,
        "The paper's SURF: 4 filter sizes per octave, --max-offset 0.5, --descriptor surf (with --octaves 2 "
        "--haar rounded: the chip's software in float); options given beside it win");
    command
        .add_option_function<int>(
            "--intervals", [&surf](const int& n) { surf.intervals = n; },
            "Filter sizes per octave, 3..8 (default 5, OpenCV's; the paper and the chip: 4)")
        ->check(CLI::Range(3, 8));
    command
        .add_option_function<std::string>(
            "--descriptor", [&surf](const std::string& d) { surf.descriptor = d; },
            "Descriptor sampling: msurf (default; OpenSURF's overlapping sub-regions) or surf (Bay's; the chip's "
            "software)")
        ->check(CLI::IsMember({"surf", "msurf"}));
    command
        .add_option_function<float>(
            "--max-offset", [&surf](const float& m) { surf.max_offset = m; },
            "The interpolation drops a maximum whose fitted offset exceeds this many samples (default 1, OpenCV's; "
            "the paper: 0.5)")
        ->check(CLI::Range(0.01f, 2.0f));
    command.add_option("--threads", surf.threads, "Threads for SURF, 0 = all cores")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
}

// --radius and --laplacian of `eval` and `eval-seq`.
CLI::Option* add_matching_options(CLI::App& command, std::optional<double>& radius, bool& laplacian) {
    command.add_flag("--laplacian", laplacian, "Match only keypoints with the same Laplacian sign");
    return command
        .add_option_function<double>(
            "--radius", [&radius](const double& r) { radius = r; },
            "Limited search: match only keypoints within PX pixels of each other (paper: 200)")
        ->check(CLI::PositiveNumber)
        ->type_name("PX");
}

CLI::App* add_surf_command(CLI::App& app, SurfCommand& c) {
    CLI::App* command =
        app.add_subcommand("surf", "Run the float reference SURF on an image and write a keypoint file");
    command->add_option("image", c.image, "Image file (any format OpenCV reads; colour is converted to grey)")
        ->required();
    command->add_option("--out,-o", c.out, "Keypoint file to write (Mikolajczyk format, plus FILE.meta)")->required();
    add_surf_options(*command, c.surf);
    command->add_flag("--no-laplacian", c.no_laplacian, "Write 64 descriptor values without the Laplacian sign column");
    command->add_flag("--quiet,-q", c.quiet, "No summary line on stderr");
    command->footer(std::string("Prints `N keypoints, threshold T, X ms` on stderr. ") + kDocs);
    return command;
}

CLI::App* add_eval_command(CLI::App& app, EvalCommand& c) {
    CLI::App* command = app.add_subcommand(
        "eval", "Distinguishability of two keypoint files; with --homography also repeatability and precision");
    command->add_option("a", c.a, "Keypoint file of image A")->required();
    command->add_option("b", c.b, "Keypoint file of image B")->required();
    CLI::Option* h = command->add_option("--homography,-H", c.homography,
                                         "Homography A -> B (Oxford text H1to3p, or OpenCV XML/YAML/JSON)");
    h->type_name("FILE");
    CLI::Option* images = command->add_option("--images", c.images, "Images A and B (repeatability needs their sizes)")
                              ->expected(2)
                              ->type_name("IMG_A IMG_B");
    h->needs(images);
    images->needs(h);
    add_matching_options(*command, c.radius, c.laplacian);
    command->footer(std::string("Prints one JSON object on stdout: candidates, valid, distinguishability, status "
                                "(RANSAC F); with --homography also repeatability, correspondences, precision, "
                                "matches, visible_a, visible_b, precision_candidates, precision_correct.\n") +
                    kDocs);
    return command;
}

CLI::App* add_eval_seq_command(CLI::App& app, EvalSeqCommand& c) {
    CLI::App* command = app.add_subcommand(
        "eval-seq", "Run SURF on every frame of a sequence and average distinguishability over frame pairs");
    command
        ->add_option("source", c.source,
                     "Video, folder of images (a ViSP folder with Images/ works too) or list file (.txt/.lst)")
        ->required();
    command->add_option("--frames", c.frames, "Use the first N frames only (0 = all)")->capture_default_str();
    command->add_option("--gap", c.gaps, "Compare frames i and i+K (repeatable; default 1)")
        ->check(CLI::PositiveNumber)
        ->type_name("K");
    add_surf_options(*command, c.surf);
    CLI::Option* poses =
        command->add_option("--poses", c.poses,
                            "Folder of Camera_<n>.txt cMo pose files (ViSP): also ground-truth F; frame n is the "
                            "image whose name ends in n");
    poses->type_name("DIR");
    CLI::Option* intrinsics = command->add_option("--intrinsics", c.intrinsics, "Camera intrinsics for --poses")
                                  ->expected(4)
                                  ->delimiter(',')
                                  ->type_name("fx,fy,u0,v0");
    poses->needs(intrinsics);
    intrinsics->needs(poses);
    add_matching_options(*command, c.radius, c.laplacian);
    command
        ->add_flag("--table", c.table,
                   "The four rows of the paper's Table II: limited search (--radius, default 200) Y/N x "
                   "Laplacian Y/N")
        ->excludes("--laplacian");
    command->add_flag("--per-pair", c.per_pair, "Also list every pair's figures in the JSON");
    CLI::Option* write =
        command->add_option("--keypoints", c.keypoints_dir, "Also write each frame's keypoint file into this folder")
            ->type_name("DIR");
    command
        ->add_option(
            "--keypoints-from", c.keypoints_from,
            "Evaluate the keypoint files in DIR instead of running SURF (sorted by name, one per frame: a run's "
            "keypoints/ folder, or another detector's)")
        ->type_name("DIR")
        ->excludes(write)
        ->excludes("--threshold")
        ->excludes("--target-count");
    command->add_flag("--quiet,-q", c.quiet, "No summary on stderr");
    command->footer(
        std::string("Prints one JSON object on stdout, a summary on stderr. Example (ViSP castle):\n"
                    "  surfvp eval-seq Castle-simu --poses Castle-simu/CameraPose --intrinsics 700,700,320,240 "
                    "--target-count 100 --gap 1 --gap 2 --table\n") +
        kDocs);
    return command;
}

CLI::App* add_draw_command(CLI::App& app, DrawCommand& c) {
    CLI::App* command =
        app.add_subcommand("draw", "Draw a keypoint file on its image: circles of radius 2.5 s with the orientation");
    command->add_option("image", c.image, "The image the keypoints were found on")->required();
    command->add_option("keypoints", c.keypoints, "Keypoint file")->required();
    command->add_option("--out,-o", c.out, "Image to write; the extension picks the format (.png)")->required();
    command->footer(std::string("Red: dark blob on light (Laplacian +1); blue: light blob (-1); yellow: sign "
                                "unknown. ") +
                    kDocs);
    return command;
}

}  // namespace

struct QualityCommands::State {
    SurfCommand surf;
    EvalCommand eval;
    EvalSeqCommand eval_seq;
    DrawCommand draw;
    CLI::App* surf_command = nullptr;
    CLI::App* eval_command = nullptr;
    CLI::App* eval_seq_command = nullptr;
    CLI::App* draw_command = nullptr;
};

// The options write into State's members, so State lives on the heap at a fixed address.
QualityCommands::QualityCommands(CLI::App& app) : state_(std::make_shared<State>()) {
    State& s = *state_;
    s.surf_command = add_surf_command(app, s.surf);
    s.eval_command = add_eval_command(app, s.eval);
    s.eval_seq_command = add_eval_seq_command(app, s.eval_seq);
    s.draw_command = add_draw_command(app, s.draw);
}

std::optional<int> QualityCommands::run() {
    State& s = *state_;
    if (*s.surf_command) return run_surf(s.surf);
    if (*s.eval_command) return run_eval(s.eval);
    if (*s.eval_seq_command) return run_eval_seq(s.eval_seq);
    if (*s.draw_command) return run_draw(s.draw);
    return std::nullopt;
}

}  // namespace surfvp
