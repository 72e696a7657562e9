// `surfvp eval-seq`: the reference SURF on every frame of a sequence, then the paper's
// distinguishability averaged over the frame pairs (i, i + gap), with F from RANSAC and, when
// camera poses are given, from the ground truth; optionally all four rows of Table II.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "platform/quality/quality_json.h"
#include "platform/quality/quality_tasks.h"
#include "platform/run/run.h"
#include "sw/eval/keypoint_file.h"
#include "sw/eval/pose_geometry.h"
#include "sw/eval/sequence.h"

namespace surfvp::quality {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// The frames to run on and, with --poses, each frame's camera pose.
struct Frames {
    eval::Sequence sequence;
    std::vector<Eigen::Matrix4d> poses;  // empty without --poses
    std::vector<std::string> skipped;    // images without a frame number (with --poses)
};

// A ViSP sequence folder (Castle-simu: Images/, CameraPose/, Depth/, ...) has no images of its
// own; its frames are in Images/.
fs::path image_source(const fs::path& source) {
    if (fs::is_directory(source) && fs::is_directory(source / "Images") && eval::list_image_folder(source).empty())
        return source / "Images";
    return source;
}

// The digits that end a file's stem: Image_0012.pgm and Camera_012.txt are both frame 12.
std::optional<unsigned> trailing_number(const fs::path& file) {
    const std::string stem = file.stem().string();
    std::size_t first = stem.size();
    while (first > 0 && std::isdigit(static_cast<unsigned char>(stem[first - 1]))) --first;
    if (first == stem.size() || stem.size() - first > 9) return std::nullopt;
    return static_cast<unsigned>(std::stoul(stem.substr(first)));
}

// Camera_<n>.txt in `folder`, by n.
std::map<unsigned, fs::path> pose_files(const fs::path& folder) {
    if (!fs::is_directory(folder)) throw ConfigError("--poses " + folder.string() + ": no such folder");
    std::map<unsigned, fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder)) {
        const fs::path& file = entry.path();
        if (file.extension() != ".txt" || file.filename().string().rfind("Camera_", 0) != 0) continue;
        const auto n = trailing_number(file);
        if (n && !files.emplace(*n, file).second)
            throw ConfigError("--poses " + folder.string() + ": two pose files for frame " + std::to_string(*n) + ": " +
                              files[*n].filename().string() + " and " + file.filename().string());
    }
    if (files.empty()) throw ConfigError("--poses " + folder.string() + ": no Camera_<n>.txt pose files");
    return files;
}

// With poses, a frame is an image whose name ends in its number n, and its pose is
// Camera_<n>.txt; frames are ordered by n. Other images (a mask, a background) are skipped.
Frames posed_frames(eval::Sequence sequence, const EvalSeqCommand& c) {
    if (sequence.kind == eval::SequenceKind::video)
        throw ConfigError("--poses: " + sequence.source.string() +
                          " is a video; ground truth needs image files numbered like the pose files "
                          "(Image_0001.pgm <-> Camera_001.txt)");
    const auto poses = pose_files(c.poses);
    std::vector<std::pair<unsigned, eval::SequenceFrame>> numbered;
    Frames frames;
    for (const auto& frame : sequence.frames) {
        if (const auto n = trailing_number(frame.image)) {
            numbered.emplace_back(*n, frame);
        } else {
            frames.skipped.push_back(frame.name);
        }
    }
    std::stable_sort(numbered.begin(), numbered.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    if (c.frames > 0 && numbered.size() > c.frames) numbered.resize(c.frames);
    sequence.frames.clear();
    for (auto& [n, frame] : numbered) {
        const auto pose = poses.find(n);
        if (pose == poses.end())
            throw ConfigError(frame.image.string() + ": no pose file Camera_<" + std::to_string(n) + ">.txt in " +
                              c.poses);
        frames.poses.push_back(read_input("--poses", [&] { return eval::read_pose_file(pose->second); }));
        frame.index = sequence.frames.size();
        sequence.frames.push_back(frame);
    }
    frames.sequence = std::move(sequence);
    return frames;
}

Frames open_frames(const EvalSeqCommand& c) {
    const fs::path source = image_source(c.source);
    // With poses the limit applies after the non-frame images are dropped.
    eval::Sequence sequence =
        read_input("", [&] { return eval::open_sequence(source, c.poses.empty() ? c.frames : 0); });
    Frames frames = c.poses.empty() ? Frames{std::move(sequence), {}, {}} : posed_frames(std::move(sequence), c);
    const std::size_t max_gap = *std::max_element(c.gaps.begin(), c.gaps.end());
    if (frames.sequence.frames.size() <= max_gap)
        throw ConfigError(c.source + ": " + std::to_string(frames.sequence.frames.size()) +
                          " frame(s) make no pair with --gap " + std::to_string(max_gap));
    return frames;
}

// keypoints/<image stem>.key, or keypoints/<video stem>_<index>.key.
fs::path keypoint_file_name(const fs::path& folder, const eval::SequenceFrame& frame, const eval::Sequence& s) {
    if (s.kind != eval::SequenceKind::video) return folder / (frame.image.stem().string() + ".key");
    char index[16];
    std::snprintf(index, sizeof index, "_%04zu.key", frame.index);
    return folder / (s.source.stem().string() + index);
}

struct FrameKeypoints {
    std::vector<surf::Keypoints> keypoints;
    std::vector<float> thresholds;
    double seconds = 0;
};

// Two images of one stem (a/x.png and b/x.png in a list, x.png and x.jpg in a folder) would
// write one keypoint file, the second over the first.
void check_keypoint_names(const Frames& frames, const EvalSeqCommand& c) {
    std::map<fs::path, fs::path> written;
    for (const eval::SequenceFrame& frame : frames.sequence.frames) {
        const fs::path file = keypoint_file_name(c.keypoints_dir, frame, frames.sequence);
        const auto [first, fresh] = written.emplace(file, frame.image);
        if (!fresh)
            throw ConfigError("--keypoints: " + first->second.string() + " and " + frame.image.string() +
                              " would both be written to " + file.string() + "; rename one");
    }
}

FrameKeypoints detect_frames(const Frames& frames, const EvalSeqCommand& c) {
    if (!c.keypoints_dir.empty()) check_keypoint_names(frames, c);
    if (!c.keypoints_dir.empty()) read_input("--keypoints", [&] { fs::create_directories(c.keypoints_dir); });
    const auto start = std::chrono::steady_clock::now();
    FrameKeypoints out;
    eval::SequenceReader reader(frames.sequence);
    cv::Mat image;
    while (read_input("", [&] { return reader.next(image); })) {
        const eval::SequenceFrame& frame = frames.sequence.frames[reader.position() - 1];
        Detection d = detect(image, c.surf, frame.name);
        if (!c.keypoints_dir.empty()) {
            const fs::path file = keypoint_file_name(c.keypoints_dir, frame, frames.sequence);
            read_input("--keypoints", [&] { eval::write_keypoint_file(file, d.keypoints); });
        }
        out.keypoints.push_back(std::move(d.keypoints));
        out.thresholds.push_back(d.threshold);
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

// Keypoints computed elsewhere (the chip's keypoints/ folder): the folder's keypoint files in
// name order, one per frame.
FrameKeypoints read_frame_keypoints(const Frames& frames, const EvalSeqCommand& c) {
    std::vector<fs::path> files;
    read_input("--keypoints-from", [&] {
        for (const auto& entry : fs::directory_iterator(c.keypoints_from))
            if (entry.is_regular_file() && entry.path().extension() != ".meta") files.push_back(entry.path());
    });
    std::sort(files.begin(), files.end());
    if (files.size() != frames.sequence.frames.size())
        throw ConfigError(fmt::format("--keypoints-from {}: {} keypoint files for {} frames of {}", c.keypoints_from,
                                      files.size(), frames.sequence.frames.size(), c.source));
    FrameKeypoints out;
    for (const fs::path& file : files) {
        out.keypoints.push_back(read_input("--keypoints-from", [&] { return eval::load_keypoints(file); }));
        out.thresholds.push_back(0);  // not known here
    }
    return out;
}

// One row of the table: how candidates are found.
std::vector<eval::RatioTestOptions> rows(const EvalSeqCommand& c) {
    auto row = [](std::optional<double> radius, bool laplacian) {
        eval::RatioTestOptions o;
        o.search_radius = radius;
        o.same_laplacian = laplacian;
        return o;
    };
    if (!c.table) return {row(c.radius, c.laplacian)};
    const double radius = c.radius.value_or(200.0);  // paper §IV-A
    return {row(radius, true), row(radius, false), row(std::nullopt, true), row(std::nullopt, false)};
}

ordered_json sequence_json(const eval::SequenceDistinguishability& s, std::size_t gap, bool per_pair) {
    ordered_json j;
    j["mean"] = s.mean;
    j["mean_of_measured"] = s.mean_of_measured;
    j["pairs"] = s.pairs.size();
    j["measured_pairs"] = s.measured_pairs;
    j["candidates"] = s.candidates;
    j["valid"] = s.valid;
    if (!per_pair) return j;
    ordered_json pairs = ordered_json::array();
    for (std::size_t i = 0; i < s.pairs.size(); ++i) {
        const auto& p = s.pairs[i];
        pairs.push_back({{"a", i},
                         {"b", i + gap},
                         {"candidates", p.candidates},
                         {"valid", p.valid},
                         {"distinguishability", p.distinguishability},
                         {"status", status_name(p.status)}});
    }
    j["per_pair"] = std::move(pairs);
    return j;
}

eval::CameraIntrinsics intrinsics(const EvalSeqCommand& c) {
    const auto& k = c.intrinsics;
    if (k[0] <= 0 || k[1] <= 0) throw ConfigError("--intrinsics: the focal lengths fx, fy must be positive");
    return {k[0], k[1], k[2], k[3]};
}

// F of frames (i, j) from their poses; coincident camera centres leave F undefined.
eval::FundamentalOfPair true_fundamental(const Frames& frames, const eval::CameraIntrinsics& k) {
    return [&frames, k](std::size_t i, std::size_t j) {
        try {
            return eval::fundamental_from_poses(k, frames.poses[i], frames.poses[j]);
        } catch (const std::invalid_argument&) {
            throw ConfigError("--poses: frames " + frames.sequence.frames[i].name + " and " +
                              frames.sequence.frames[j].name + " have the same camera centre, so no F");
        }
    };
}

ordered_json row_json(const std::vector<surf::Keypoints>& keypoints, std::size_t gap,
                      const eval::RatioTestOptions& matching, const Frames& frames, const EvalSeqCommand& c) {
    eval::DistinguishabilityOptions options;
    options.matching = matching;
    const auto ransac = eval::sequence_distinguishability(keypoints, gap, options);
    ordered_json j = matching_json(matching);
    j.update(sequence_json(ransac, gap, c.per_pair));
    if (frames.poses.empty()) return j;
    const auto truth =
        eval::sequence_distinguishability(keypoints, gap, true_fundamental(frames, intrinsics(c)), options);
    j["ground_truth"] = sequence_json(truth, gap, c.per_pair);
    j["ransac_minus_ground_truth"] = ransac.mean - truth.mean;
    return j;
}

ordered_json surf_json(const SurfSettings& s, const FrameKeypoints& detected) {
    std::size_t total = 0, least = SIZE_MAX, most = 0;
    for (const auto& k : detected.keypoints) {
        total += k.size();
        least = std::min(least, k.size());
        most = std::max(most, k.size());
    }
    const auto [t_min, t_max] = std::minmax_element(detected.thresholds.begin(), detected.thresholds.end());
    ordered_json j;
    j["threshold"] = s.threshold ? ordered_json(*s.threshold) : nullptr;
    j["target_count"] = s.target_count ? ordered_json(*s.target_count) : nullptr;
    j["upright"] = s.upright;
    const surf::Params p = s.params();
    j["octaves"] = s.octaves;
    j["intervals"] = p.intervals;
    j["init_step"] = s.init_step;
    j["haar"] = s.haar;
    j["descriptor"] = p.descriptor == surf::DescriptorKind::msurf ? "msurf" : "surf";
    j["max_offset"] = p.max_offset;
    j["keypoints"] = {{"total", total},
                      {"mean", static_cast<double>(total) / static_cast<double>(detected.keypoints.size())},
                      {"min", least},
                      {"max", most}};
    j["thresholds"] = {{"min", *t_min}, {"max", *t_max}};
    j["seconds"] = detected.seconds;
    return j;
}

void print_summary(const ordered_json& out) {
    const auto& k = out["surf"]["keypoints"];
    std::fprintf(stderr, "%zu frames, %.1f keypoints per frame (%zu..%zu), %s\n", out["frames"].get<std::size_t>(),
                 k["mean"].get<double>(), k["min"].get<std::size_t>(), k["max"].get<std::size_t>(),
                 out["surf"].contains("seconds")
                     ? fmt::format("SURF {:.1f} s", out["surf"]["seconds"].get<double>()).c_str()
                     : ("from " + out["surf"]["keypoints_from"].get<std::string>()).c_str());
    for (const auto& gap : out["gaps"]) {
        for (const auto& row : gap["rows"]) {
            const auto& radius = row["search_radius"];
            const std::string radius_text = radius.is_null() ? "-" : fmt::format("{:g}", radius.get<double>());
            std::fprintf(stderr, "gap %zu  radius %-4s  Laplacian %s  %.3f (%zu/%zu pairs measured)",
                         gap["gap"].get<std::size_t>(), radius_text.c_str(),
                         row["same_laplacian"].get<bool>() ? "Y" : "N", row["mean"].get<double>(),
                         row["measured_pairs"].get<std::size_t>(), row["pairs"].get<std::size_t>());
            if (row.contains("ground_truth"))
                std::fprintf(stderr, "  ground truth %.3f  difference %+.3f", row["ground_truth"]["mean"].get<double>(),
                             row["ransac_minus_ground_truth"].get<double>());
            std::fputc('\n', stderr);
        }
    }
}

}  // namespace

int run_eval_seq(const EvalSeqCommand& command) {
    EvalSeqCommand c = command;
    if (c.gaps.empty()) c.gaps = {1};
    const Frames frames = open_frames(c);
    const FrameKeypoints detected =
        c.keypoints_from.empty() ? detect_frames(frames, c) : read_frame_keypoints(frames, c);

    ordered_json out;
    out["source"] = c.source;
    out["frames"] = frames.sequence.frames.size();
    out["first_frame"] = frames.sequence.frames.front().name;
    out["last_frame"] = frames.sequence.frames.back().name;
    out["skipped"] = frames.skipped;
    out["poses"] = c.poses.empty() ? ordered_json(nullptr) : ordered_json(c.poses);
    out["intrinsics"] = c.poses.empty() ? ordered_json(nullptr) : ordered_json(c.intrinsics);
    out["surf"] = surf_json(c.surf, detected);
    if (!c.keypoints_from.empty())
        out["surf"] = {{"keypoints_from", c.keypoints_from}, {"keypoints", out["surf"]["keypoints"]}};
    out["gaps"] = ordered_json::array();
    for (const std::size_t gap : c.gaps) {
        ordered_json table = ordered_json::array();
        for (const auto& matching : rows(c)) table.push_back(row_json(detected.keypoints, gap, matching, frames, c));
        out["gaps"].push_back({{"gap", gap}, {"rows", std::move(table)}});
    }
    std::cout << out.dump(2) << std::endl;
    if (!c.quiet) print_summary(out);
    return kExitOk;
}

}  // namespace surfvp::quality
