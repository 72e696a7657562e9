// docs/errors.md, row by row: every class of bad input, through the real binary. Each ends
// with one line on stderr that starts "surfvp: error:" (a refused write: "surfvp: cannot
// write:") and names the file, line and key; no library noise comes before it; the exit code
// is 2 (4 for a refused write); nothing is written.
#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <sys/stat.h>
#include <vector>

#include "cli.h"

namespace surfvp::test {
namespace {
namespace fs = std::filesystem;

const std::string kGraf1 = std::string(OPENCV_DATA_DIR) + "/graf1.png";  // 800x640
const std::string kCastle = std::string(VISP_DATA_DIR) + "/mbt-depth/Castle-simu";

std::string first_line(const std::string& err) { return err.substr(0, err.find('\n')); }

// The outcome every row promises: the exit code, one line with the prefix, the words in it.
void expect_refused(const Cli& r, const std::vector<std::string>& words, const std::string& what, int code = 2) {
    EXPECT_EQ(r.exit_code, code) << what << ": " << r.err;
    const std::string line = first_line(r.err);
    const std::string prefix = code == 4 ? "surfvp: cannot write: " : "surfvp: error: ";
    EXPECT_EQ(line.rfind(prefix, 0), 0u) << what << ": " << r.err;
    for (const std::string& w : words)
        EXPECT_NE(line.find(w), std::string::npos) << what << ": '" << w << "' not in: " << line;
    const auto lines = std::count(r.err.begin(), r.err.end(), '\n');
    EXPECT_EQ(lines, r.err.find("Run with --help") == std::string::npos ? 1 : 2) << what << ": nothing else: " << r.err;
}

std::string scenario(const std::string& text) { return write_file(fresh_dir("scenario"), "s.yaml", text); }

// A SURF scenario: surf.source on line 5, surf.frames on 6, surf.width and height (0: the
// frames' own size) on 7 and 8, no budget; `more` from line 11.
std::string surf_scenario(const std::string& dir, const std::string& source, const std::string& more = "") {
    static int made = 0;
    return write_file(dir, "surf_" + std::to_string(++made) + ".yaml",
                      "name: errors\nrun:\n  workload: surf\nsurf:\n  source: " + source +
                          "\n  frames: 2\n  width: 0\n  height: 0\nbudget:\n  fps: 0\n" + more);
}

std::string image(const std::string& dir, const std::string& name, int width, int height) {
    const std::string path = (fs::path(dir) / name).string();
    cv::Mat m(height, width, CV_8UC1);
    cv::randu(m, 0, 255);
    cv::imwrite(path, m);
    return path;
}

std::string bytes_of(const std::string& path, size_t n) { return slurp(path).substr(0, n); }

TEST(BadInput, ScenarioSyntaxNamesFileAndLine) {
    const std::string bracket = scenario("plb1:\n  clock: [100 MHz\n");
    expect_refused(surfvp("validate " + bracket), {bracket + ":", "not valid YAML"}, "unclosed list");
    const std::string list = scenario("- cpu\n- plb1\n");
    expect_refused(surfvp("validate " + list), {list + ":1", "a scenario is a map of sections"}, "a list");
    // yaml-cpp 0.7 never returns on a ',' where a node begins (found by tests/fuzz scenario):
    // refused with its line, in a file and in --set faults.
    const std::string comma = scenario("# a scenario\n,: e!Un\n");
    expect_refused(surfvp("validate " + comma), {comma + ":2", "not valid YAML", "a ',' where a node begins"},
                   "a comma");
    expect_refused(surfvp("validate smoke --set faults=,"), {"--set faults: not a YAML list"}, "a comma in --set");
    const std::string key = scenario("cpu:\n  ? [a, b]\n  : 1\n");
    expect_refused(surfvp("validate " + key), {key + ":2", "a key must be a plain name, not a list"},
                   "a list as a key");
}

TEST(BadInput, ScenarioFileMissingAFolderOrNotARegularFile) {
    const std::string dir = fresh_dir("scenario_files");
    expect_refused(surfvp("validate " + dir + "/none.yaml"), {dir + "/none.yaml: no such scenario file"}, "missing");
    expect_refused(surfvp("validate " + dir), {dir + ": is a folder, not a scenario file"}, "folder");
    // Root reads every file: a FIFO stands in for one that cannot be read (it would block).
    const std::string fifo = dir + "/fifo.yaml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expect_refused(surfvp("validate " + fifo), {fifo + ": is not a regular file"}, "FIFO");
}

TEST(BadInput, RepeatedKeysInAnySectionNameBothPlaces) {
    const std::string name = scenario("name: a\nname: b\n");
    expect_refused(surfvp("validate " + name), {name + ":2: 'name' appears twice (first at " + name + ":1)"}, "name");
    const std::string text = scenario("description: a\ncpu:\n  clock: 300 MHz\ndescription: b\n");
    expect_refused(surfvp("validate " + text), {text + ":4: 'description' appears twice (first at " + text + ":1)"},
                   "description");
    const std::string section = scenario("cpu:\n  clock: 300 MHz\ncpu:\n  quantum: 1 us\n");
    expect_refused(surfvp("validate " + section),
                   {section + ":3: section 'cpu' appears twice (first at " + section + ":1)"}, "section");
    const std::string key = scenario("plb2:\n  width: 64 bit\n  clock: 1 MHz\n  width: 32 bit\n");
    expect_refused(surfvp("validate " + key), {key + ":4: plb2.width is set twice (first at " + key + ":2)"}, "key");
    expect_refused(surfvp("validate smoke --set 'cpu.clock=300 MHz' --set 'cpu.clock=400 MHz'"),
                   {"--set cpu.clock: given twice ('300 MHz', then '400 MHz')"}, "--set");
}

TEST(BadInput, SeveralYamlDocumentsInOneFile) {
    const std::string path = scenario("name: a\ncpu:\n  clock: 300 MHz\n---\nname: b\n");
    expect_refused(surfvp("validate " + path), {path + ": holds 2 YAML documents", "line 5", "a scenario is one"},
                   "two");
}

TEST(BadInput, UnknownKeyNamesTheClosestKnownOne) {
    const std::string path = scenario("plb2:\n  widht: 64 bit\n");
    expect_refused(surfvp("validate " + path),
                   {path + ":2", "'plb2.widht' is not a parameter", "did you mean 'plb2.width'"}, "misspelt");
    expect_refused(surfvp("validate smoke --set cpu.clok=1MHz"), {"--set", "'cpu.clok'", "did you mean 'cpu.clock'"},
                   "--set");
}

TEST(BadInput, WrongOrMissingUnit) {
    const std::string wrong = scenario("cpu:\n  clock: 300 bit\n");
    expect_refused(surfvp("validate " + wrong), {wrong + ":2: cpu.clock", "wrong unit 'bit'", "expected frequency"},
                   "wrong");
    const std::string none = scenario("memory:\n  latency: 25\n");
    expect_refused(surfvp("validate " + none), {none + ":2: memory.latency", "has no unit"}, "missing");
}

TEST(BadInput, OutOfRangeAtAnyMagnitude) {
    for (const char* line :
         {"surf:\n  frames: 1e400\n", "surf:\n  frames: -3\n", "smoke:\n  src: 0xFFFF_FFFF_FFFF_FFFF_FFFF\n",
          "smoke:\n  src: 0x1_0000_0000\n", "plb1:\n  max_burst: 32 beats\n"}) {
        const std::string path = scenario(line);
        expect_refused(surfvp("validate " + path), {path + ":2", "out of range", "must be between"}, line);
    }
    // NaN, infinities and values their type cannot hold: Environment.ValuesThatDoNotFitOrAreNotNumbersAreBadInput.
}

TEST(BadInput, InconsistentParametersAreReportedAtTheirOrigin) {
    const std::string dir = fresh_dir("inconsistent");
    const std::string surf = surf_scenario(dir, kGraf1);
    expect_refused(
        surfvp("validate " + surf + " --set surf.width=512"),
        {"--set surf.width: 512 with surf.height = 0 (from " + surf + ":8)", "resized only when both are set"},
        "half a size");
    const std::string fault = surf_scenario(dir, kGraf1, "faults:\n  - {kind: fifo_overflow, frame: 5}\n");
    expect_refused(
        surfvp("validate " + fault),
        {fault + ":12: faults: fifo_overflow on fhg, frame 5: past the last frame (surf.frames = 2: frames 0 to 1)"},
        "fault");
    const std::string eval =
        surf_scenario(dir, kGraf1, "eval:\n  homography: " + std::string(OPENCV_DATA_DIR) + "/H1to3p.xml\n");
    expect_refused(surfvp("validate " + eval + " --set surf.frames=1"),
                   {eval + ":12: eval.homography", "surf.frames is 1 (from --set)", "at least 2"}, "evaluation");
    const std::string plb = scenario("plb2:\n  width: 48 bit\n");
    expect_refused(surfvp("validate " + plb), {plb + ":2: plb2.width: 48 bit: a PLB is 32, 64 or 128 bit wide"}, "PLB");
    expect_refused(surfvp("validate smoke --set soc.accelerators=4 --set intc.inputs=8"),
                   {"--set intc.inputs: 8 inputs are too few for 4 accelerator pairs", "they need 9"}, "INTC");
    expect_refused(surfvp("validate " + kBudget + " --set 'memory.size=1 MiB'"),
                   {"--set memory.size: 2 buffer sets (surf.tasks_in_flight, from the default) for frames of 1024x768",
                    "memory.size is 1 MiB"},
                   "memory");
    // A model's own refusal (the FHG's fixed-point formats, its read sequence) names where each
    // parameter it names came from, and comes before a run makes its folder.
    expect_refused(surfvp("validate " + kBudget + " --set 'fhg.det_frac_bits=48 bit'"),
                   {"fhg precision: det_frac_bits must not exceed 2 x response_frac_bits",
                    "fhg.det_frac_bits = 48 bit from --set", "fhg.response_frac_bits = 9 bit from the default"},
                   "precision");
    const std::string out = fresh_path("inconsistent_out");
    expect_refused(surfvp("run " + kBudget + kOneRun + " --quiet --out " + out + " --set fhg.line_fifo=sdp72"),
                   {"fhg.line_fifo: sdp72 serves 1 aligned pair", "fhg.line_fifo = sdp72 from --set"}, "sequence");
    EXPECT_FALSE(fs::exists(out)) << "an empty output folder was made";
    expect_refused(surfvp("validate " + kBudget + " --set surf.frames=1"),
                   {"--set surf.frames: 1 frames cannot give a frame rate", "budget.fps = 0 (from " + kBudget + ":12)"},
                   "budget");
}

TEST(BadInput, AParameterWithoutEffectIsAStatedWarning) {
    const auto threshold = surfvp("validate " + kBudget + " --set surf.threshold=300");
    EXPECT_EQ(threshold.exit_code, 0) << threshold.err;
    EXPECT_EQ(
        first_line(threshold.err),
        "surfvp: warning: --set surf.threshold = 300 has no effect: surf.target_keypoints is 100, so the threshold "
        "is calibrated on frame 0");
    EXPECT_EQ(surfvp("validate " + kBudget + " --set surf.threshold=500").err, "") << "at its default: nothing to say";

    const std::string out = fresh_dir("ineffective");
    const auto run = surfvp("run smoke --quiet --trace none --out " + out + " --set surf.frames=3");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err, "surfvp: warning: --set surf.frames = 3 has no effect: run.workload is smoke\n");
    EXPECT_NE(slurp(out + "/config.yaml").find("frames: 3  # --set; no effect: run.workload is smoke"),
              std::string::npos)
        << slurp(out + "/config.yaml");
}

TEST(BadInput, SourceMissingEmptyCorruptOrUnreadable) {
    const std::string dir = fresh_dir("source");
    const std::string empty = write_file(dir, "empty.png", "");
    const std::string corrupt = write_file(dir, "corrupt.png", "not a PNG at all");
    const std::string truncated = write_file(dir, "truncated.png", bytes_of(kGraf1, 2000));  // libpng complains
    const std::string folder = dir + "/no_images";
    fs::create_directories(folder);
    const std::string fifo = dir + "/fifo.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::vector<std::pair<std::string, std::string>> cases{
        {dir + "/none.png", "no such file or folder"}, {empty, "file is empty (0 bytes)"},
        {corrupt, "not an image OpenCV can decode"},   {truncated, "not an image OpenCV can decode"},
        {folder, "no image files in the folder"},      {fifo, "not a regular file or a folder"}};
    for (const auto& [source, problem] : cases) {
        const std::string path = surf_scenario(dir, source);
        expect_refused(surfvp("validate " + path), {path + ":5: surf.source: " + source, problem}, source);
    }
    const std::string corrupt_video = write_file(dir, "corrupt.avi", "RIFF, but no video");
    const std::string path = surf_scenario(dir, corrupt_video);
    expect_refused(surfvp("validate " + path), {path + ":5: surf.source", "a video that OpenCV can open"}, "video");
}

TEST(BadInput, FramesTooSmallForTheFiltersOrLargerThanTheChipTakes) {
    const std::string dir = fresh_dir("sizes");
    const std::string tiny = surf_scenario(dir, image(dir, "tiny.png", 16, 16));
    expect_refused(surfvp("validate " + tiny), {tiny + ":5: surf.source", "16x16 is too small", "at least 30x30"},
                   "tiny");
    const std::string wide = surf_scenario(dir, image(dir, "wide.png", 1100, 64));
    expect_refused(surfvp("validate " + wide),
                   {wide + ":5: surf.source: frames of 1100x64 are larger than the chip takes: iig.max_width is 1024 "
                           "(from the default)"},
                   "wide");
    const std::string graf = surf_scenario(dir, kGraf1);
    expect_refused(surfvp("validate " + graf + " --set surf.width=16 --set surf.height=16"),
                   {"--set surf.width: frames resized to 16x16", "too small"}, "resized");
    expect_refused(surfvp("validate " + graf + " --set fhg.max_height=600"),
                   {graf + ":5: surf.source: frames of 800x640", "fhg.max_height is 600 (from --set)"}, "limit");
}

TEST(BadInput, FewerFramesThanAskedOrFramesThatDoNotMatch) {
    const std::string dir = fresh_dir("frames");
    const std::string a = image(dir, "a.png", 64, 64), b = image(dir, "b.png", 80, 64);
    const std::string two = write_file(dir, "two.txt", a + "\n" + a + "\n");
    const std::string few = surf_scenario(dir, two);
    expect_refused(surfvp("validate " + few + " --set surf.frames=3"),
                   {few + ":5: surf.source: surf.frames is 3 (from --set), but " + two + " has only 2"}, "list");
    const std::string video = write_file(dir, "short.avi", bytes_of(std::string(OPENCV_DATA_DIR) + "/vtest.avi", 5000));
    const std::string cut = surf_scenario(dir, video);
    expect_refused(surfvp("validate " + cut + " --set surf.frames=50"),
                   {cut + ":5: surf.source: surf.frames is 50 (from --set), but " + video + " has only"}, "video");
    // Frames of different sizes go through one run (tests/platform/frame_sizes_test.cpp); one the
    // chip cannot take is named.
    const std::string mixed = surf_scenario(dir, write_file(dir, "mixed.txt", a + "\n" + b + "\n"));
    EXPECT_EQ(surfvp("validate " + mixed).exit_code, 0) << "sizes may differ";
    const std::string tiny = image(dir, "tiny.png", 80, 20);
    const std::string small = surf_scenario(dir, write_file(dir, "small.txt", a + "\n" + tiny + "\n"));
    expect_refused(surfvp("validate " + small), {"frame 1 (" + tiny + ") of 80x20 is too small"}, "sizes");
    const std::string list = write_file(dir, "missing.txt", a + "\n" + dir + "/gone.png\n");
    const std::string missing = surf_scenario(dir, list);
    expect_refused(surfvp("validate " + missing),
                   {missing + ":5: surf.source: " + list + ":2: image '" + dir + "/gone.png' does not exist"},
                   "list entry");
}

TEST(BadInput, HomographyMissingEmptyCorruptSingularOrForOtherFrames) {
    const std::string dir = fresh_dir("homography");
    fs::create_directories(dir + "/folder");
    const std::vector<std::pair<std::string, std::string>> cases{
        {dir + "/none", "no such file"},
        {write_file(dir, "empty.txt", ""), "file ends after 0 of the 3 rows"},
        {write_file(dir, "short.txt", "1 0 0\n0 1 0\n"), "short.txt:2: file ends after 2 of the 3 rows"},
        {write_file(dir, "words.txt", "1 0 0\n0 one 0\n0 0 1\n"), "words.txt:2"},
        {write_file(dir, "singular.txt", "1 0 0\n0 1 0\n0 0 0\n"), "the homography is singular"},
        {dir + "/folder", "not a regular file"}};
    for (const auto& [file, problem] : cases) {
        const std::string path = surf_scenario(dir, kGraf1, "eval:\n  homography: " + file + "\n");
        expect_refused(surfvp("validate " + path), {path + ":12: eval.homography: " + file, problem}, file);
    }
    const std::string good =
        surf_scenario(dir, kGraf1, "eval:\n  homography: " + std::string(OPENCV_DATA_DIR) + "/H1to3p.xml\n");
    expect_refused(surfvp("validate " + good + " --set surf.width=400 --set surf.height=320"),
                   {good + ":12: eval.homography", "at their own size (800x640)", "resize them to 400x320"}, "resized");
}

TEST(BadInput, PosesMissingTooFewOrOfOtherFrames) {
    const std::string dir = fresh_dir("poses");
    const std::string images = kCastle + "/Images";
    for (const std::string sub : {"Images", "CameraPose"}) fs::create_directories(dir + "/two/" + sub);
    for (const char* n : {"1", "2"}) {
        fs::copy_file(kCastle + "/Images/Image_000" + n + ".pgm", dir + "/two/Images/Image_000" + n + ".pgm");
        fs::copy_file(kCastle + "/CameraPose/Camera_00" + n + ".txt", dir + "/two/CameraPose/Camera_00" + n + ".txt");
    }
    const std::string few = surf_scenario(dir, images, "eval:\n  poses: " + dir + "/two\n");
    expect_refused(surfvp("validate " + few + " --set surf.frames=3"),
                   {few + ":12: eval.poses: 2 poses for 3 frames (surf.frames from --set)"}, "too few");
    const std::string none = surf_scenario(dir, images, "eval:\n  poses: " + dir + "/none\n");
    expect_refused(surfvp("validate " + none), {none + ":12: eval.poses: " + dir + "/none/Images: no such folder"},
                   "missing");
    const std::string single = surf_scenario(dir, kGraf1, "eval:\n  poses: " + kCastle + "\n");
    expect_refused(surfvp("validate " + single), {single + ":12: eval.poses", "is one image or a video"}, "one image");
    // Three frames, one camera position: no geometry between them (was: exit 3 after simulating).
    for (const std::string sub : {"Images", "CameraPose"}) fs::create_directories(dir + "/still/" + sub);
    for (const char* n : {"1", "2", "3"}) {
        fs::copy_file(kCastle + "/Images/Image_000" + n + ".pgm", dir + "/still/Images/Image_000" + n + ".pgm");
        fs::copy_file(kCastle + "/CameraPose/Camera_001.txt", dir + "/still/CameraPose/Camera_00" + n + ".txt");
    }
    const std::string still = surf_scenario(dir, dir + "/still/Images", "eval:\n  poses: " + dir + "/still\n");
    expect_refused(surfvp("validate " + still + " --set surf.frames=3"),
                   {still + ":12: eval.poses: frames 0 and 1", "the camera centres coincide"}, "one place");
    const std::string swapped =
        write_file(dir, "swapped.txt", images + "/Image_0002.pgm\n" + images + "/Image_0001.pgm\n");
    const std::string other = surf_scenario(dir, swapped, "eval:\n  poses: " + kCastle + "\n");
    expect_refused(
        surfvp("validate " + other),
        {other + ":12: eval.poses: frame 0 is " + images + "/Image_0002.pgm, but pose 0 (Camera_001.txt) belongs to"},
        "other frames");
}

TEST(BadInput, NamesThatWouldWriteOutsideTheOutputFolder) {
    const std::string escape = "surfvp_escape_" + std::to_string(::getpid());
    const std::string path = scenario("name: ../" + escape + "\n");
    expect_refused(surfvp("run " + path + " --quiet --trace none"),
                   {path + ":1: name '../" + escape + "' cannot name the output folder traces/<name>"}, "name");
    EXPECT_FALSE(fs::exists(escape)) << "traces/../" << escape << " written";

    // eval-seq names keypoint files after the images: two of one stem would share one.
    const std::string dir = fresh_dir("stems");
    fs::create_directories(dir + "/a");
    fs::create_directories(dir + "/b");
    const std::string a = image(dir + "/a", "x.png", 64, 64), b = image(dir + "/b", "x.png", 64, 64);
    const std::string list = write_file(dir, "list.txt", a + "\n" + b + "\n");
    expect_refused(surfvp("eval-seq " + list + " --keypoints " + dir + "/keys"),
                   {"--keypoints: " + a + " and " + b + " would both be written to " + dir + "/keys/x.key"}, "stems");
    EXPECT_FALSE(fs::exists(dir + "/keys"));
}

TEST(BadInput, AnOutputFolderThatCannotBeWrittenHasItsOwnExitCode) {
    // Root writes anywhere a disk is: /proc is no disk. A full disk:
    // Environment.AFullDiskWhileTracingEndsWithItsOwnExitCodeAndNoPartialFile.
    const std::string proc = "/proc/surfvp_" + std::to_string(::getpid());
    expect_refused(surfvp("run smoke --quiet --trace none --out " + proc),
                   {"--out " + proc + ": cannot create the folder"}, "/proc", 4);
    const std::string file = write_file(fresh_dir("out_file"), "taken", "a file");
    expect_refused(surfvp("run smoke --quiet --trace none --out " + file),
                   {"--out " + file + ": cannot create the folder"}, "a file", 4);
    EXPECT_EQ(slurp(file), "a file");
}

TEST(BadInput, CommandLine) {
    expect_refused(surfvp("run"), {"scenario is required"}, "no scenario");
    expect_refused(surfvp("run smoke --trace some"), {"--trace: some not in"}, "--trace");
    expect_refused(surfvp("frobnicate"), {"'frobnicate' is not a command"}, "command");
    expect_refused(surfvp("validate smoke --set plb2.width"), {"--set 'plb2.width': expected KEY=VALUE"}, "--set");
}

// What a run could have found before simulating it finds before: exit 2, no output folder,
// where it used to simulate and then fail (exit 3, or 1 from the chip refusing the frame).
TEST(BadInput, ARunFindsNothingAfterSimulatingThatItCouldHaveFoundBefore) {
    const std::string dir = fresh_dir("before");
    const std::string quick = " --quiet --trace none";
    const std::vector<std::pair<std::string, std::string>> cases{
        {surf_scenario(dir, kGraf1, "eval:\n  homography: " + dir + "/none\n"), ":12: eval.homography"},
        {surf_scenario(dir, kCastle + "/Images", "eval:\n  poses: " + dir + "/none\n"), ":12: eval.poses"},
        {surf_scenario(dir, image(dir, "wide.png", 1100, 64)), ":5: surf.source"}};
    for (size_t i = 0; i < cases.size(); ++i) {
        const std::string out = fresh_path("before_out_" + std::to_string(i));
        const auto& [path, where] = cases[i];
        expect_refused(surfvp("run " + path + quick + " --out " + out), {path + where}, where);
        EXPECT_FALSE(fs::exists(out)) << where;
        expect_refused(surfvp("run " + path + quick + " --direct --out " + out), {path + where}, where + " direct");
        EXPECT_FALSE(fs::exists(out)) << where;
    }
}

}  // namespace
}  // namespace surfvp::test
