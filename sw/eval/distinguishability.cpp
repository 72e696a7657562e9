#include "sw/eval/distinguishability.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace surfvp::eval {

namespace {

Eigen::Vector2d position(const surf::Keypoint& k) { return {k.x, k.y}; }

DistinguishabilityResult with_candidates(const surf::Keypoints& a, const surf::Keypoints& b,
                                         const RatioTestOptions& options) {
    DistinguishabilityResult result;
    result.candidate_pairs = ratio_test_candidates(a, b, options);
    result.candidates = result.candidate_pairs.size();
    return result;
}

// Counts the candidates within the threshold of their epipolar lines.
void validate(const surf::Keypoints& a, const surf::Keypoints& b, const Eigen::Matrix3d& f, double threshold,
              DistinguishabilityResult& result) {
    result.fundamental = f;
    result.valid = 0;
    result.epipolar_distances.clear();
    for (const auto& c : result.candidate_pairs) {
        double d = epipolar_distance(f, position(a[c.a]), position(b[c.b]));
        result.epipolar_distances.push_back(d);
        if (d <= threshold) ++result.valid;
    }
    result.status = DistinguishabilityStatus::ok;
    result.distinguishability = static_cast<double>(result.valid) / static_cast<double>(result.candidates);
}

SequenceDistinguishability summarise(std::vector<DistinguishabilityResult> pairs) {
    SequenceDistinguishability s;
    double sum = 0;
    for (const auto& p : pairs) {
        sum += p.distinguishability;
        s.candidates += p.candidates;
        s.valid += p.valid;
        if (p.status == DistinguishabilityStatus::ok) ++s.measured_pairs;
    }
    if (!pairs.empty()) s.mean = sum / static_cast<double>(pairs.size());
    if (s.measured_pairs > 0) s.mean_of_measured = sum / static_cast<double>(s.measured_pairs);
    s.pairs = std::move(pairs);
    return s;
}

void check_gap(std::size_t gap) {
    if (gap == 0) throw std::invalid_argument("sequence_distinguishability: gap must be >= 1");
}

}  // namespace

double epipolar_distance(const Eigen::Matrix3d& fundamental, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    Eigen::Vector3d line = fundamental * a.homogeneous();
    double norm = std::hypot(line.x(), line.y());
    if (!(norm > 0)) return std::numeric_limits<double>::infinity();
    return std::abs(line.dot(b.homogeneous())) / norm;
}

std::optional<Eigen::Matrix3d> estimate_fundamental(const std::vector<Eigen::Vector2d>& a,
                                                    const std::vector<Eigen::Vector2d>& b, const RansacParams& params) {
    if (a.size() != b.size()) throw std::invalid_argument("estimate_fundamental: sizes differ");
    if (a.size() < kMinCandidatesForRansac) return std::nullopt;
    std::vector<cv::Point2d> pa, pb;
    for (std::size_t i = 0; i < a.size(); ++i) {
        pa.emplace_back(a[i].x(), a[i].y());
        pb.emplace_back(b[i].x(), b[i].y());
    }
    cv::setRNGSeed(params.seed);
    cv::Mat f =
        cv::findFundamentalMat(pa, pb, cv::FM_RANSAC, params.threshold, params.confidence, params.max_iterations);
    if (f.rows != 3 || f.cols != 3) return std::nullopt;
    Eigen::Matrix3d result;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) result(r, c) = f.at<double>(r, c);
    return result;
}

DistinguishabilityResult distinguishability(const surf::Keypoints& a, const surf::Keypoints& b,
                                            const DistinguishabilityOptions& options) {
    DistinguishabilityResult result = with_candidates(a, b, options.matching);
    if (result.candidates == 0) return result;
    if (result.candidates < kMinCandidatesForRansac) {
        result.status = DistinguishabilityStatus::too_few_candidates;
        return result;
    }
    std::vector<Eigen::Vector2d> pa, pb;
    for (const auto& c : result.candidate_pairs) {
        pa.push_back(position(a[c.a]));
        pb.push_back(position(b[c.b]));
    }
    auto f = estimate_fundamental(pa, pb, options.ransac);
    if (!f) {
        result.status = DistinguishabilityStatus::no_fundamental;
        return result;
    }
    validate(a, b, *f, options.epipolar_threshold, result);
    return result;
}

DistinguishabilityResult distinguishability(const surf::Keypoints& a, const surf::Keypoints& b,
                                            const Eigen::Matrix3d& fundamental,
                                            const DistinguishabilityOptions& options) {
    DistinguishabilityResult result = with_candidates(a, b, options.matching);
    if (result.candidates == 0) return result;
    validate(a, b, fundamental, options.epipolar_threshold, result);
    return result;
}

SequenceDistinguishability sequence_distinguishability(const std::vector<surf::Keypoints>& frames, std::size_t gap,
                                                       const DistinguishabilityOptions& options) {
    check_gap(gap);
    std::vector<DistinguishabilityResult> pairs;
    for (std::size_t i = 0; i + gap < frames.size(); ++i) {
        pairs.push_back(distinguishability(frames[i], frames[i + gap], options));
    }
    return summarise(std::move(pairs));
}

SequenceDistinguishability sequence_distinguishability(const std::vector<surf::Keypoints>& frames, std::size_t gap,
                                                       const FundamentalOfPair& fundamental,
                                                       const DistinguishabilityOptions& options) {
    check_gap(gap);
    std::vector<DistinguishabilityResult> pairs;
    for (std::size_t i = 0; i + gap < frames.size(); ++i) {
        pairs.push_back(distinguishability(frames[i], frames[i + gap], fundamental(i, i + gap), options));
    }
    return summarise(std::move(pairs));
}

}  // namespace surfvp::eval
