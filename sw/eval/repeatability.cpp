#include "sw/eval/repeatability.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

#include <Eigen/Dense>

#include "sw/eval/homography.h"
#include "sw/eval/region.h"

namespace surfvp::eval {

namespace {

// The mapped region, or nothing where the homography sends the point to or behind infinity.
std::optional<Ellipse> mapped_region(const Ellipse& e, const Eigen::Matrix3d& h) {
    if (!((h * e.centre.homogeneous()).z() > 0)) return std::nullopt;
    Ellipse mapped = map_ellipse(e, h);
    if (!mapped.centre.allFinite() || !mapped.m.allFinite() || !(mapped.m.determinant() > 0) || !(mapped.m(0, 0) > 0)) {
        return std::nullopt;
    }
    return mapped;
}

struct Visible {
    std::vector<std::size_t> index;  // into the keypoint set
    std::vector<Ellipse> in_a;       // the region in A's image
};

// Regions inside their own image and, mapped through `h`, inside the other.
Visible visible_regions(const surf::Keypoints& keypoints, const Eigen::Matrix3d& h, const cv::Size& own,
                        const cv::Size& other, bool own_is_a) {
    Visible v;
    for (std::size_t i = 0; i < keypoints.size(); ++i) {
        Ellipse region = keypoint_region(keypoints[i]);
        auto mapped = mapped_region(region, h);
        if (!mapped || !region_visible(region, own) || !region_visible(*mapped, other)) continue;
        v.index.push_back(i);
        v.in_a.push_back(own_is_a ? region : *mapped);
    }
    return v;
}

// Exact shortcuts that leave the result unchanged: the overlap is at most the ratio of the
// smaller area to the larger, and zero when the bounding boxes are apart.
bool cannot_overlap(const Ellipse& a, const Ellipse& b, double min_overlap) {
    double area_a = a.area(), area_b = b.area();
    if (std::min(area_a, area_b) / std::max(area_a, area_b) <= min_overlap) return true;
    Eigen::Vector2d gap = (a.centre - b.centre).cwiseAbs() - a.half_extent() - b.half_extent();
    return gap.x() >= 0 || gap.y() >= 0;
}

std::vector<RegionMatch> greedy_one_to_one(std::vector<RegionMatch> pairs, std::size_t na, std::size_t nb) {
    std::sort(pairs.begin(), pairs.end(), [](const RegionMatch& x, const RegionMatch& y) {
        return std::tie(x.overlap_error, x.a, x.b) < std::tie(y.overlap_error, y.a, y.b);
    });
    std::vector<bool> used_a(na, false), used_b(nb, false);
    std::vector<RegionMatch> matches;
    for (const auto& p : pairs) {
        if (used_a[p.a] || used_b[p.b]) continue;
        used_a[p.a] = used_b[p.b] = true;
        matches.push_back(p);
    }
    return matches;
}

}  // namespace

Ellipse keypoint_region(const surf::Keypoint& k) { return Ellipse::circle({k.x, k.y}, region_radius(k)); }

bool region_visible(const Ellipse& region, const cv::Size& image) {
    Eigen::Vector2d low = region.centre - region.half_extent();
    Eigen::Vector2d high = region.centre + region.half_extent();
    return low.x() > 0 && low.y() > 0 && high.x() < image.width && high.y() < image.height;
}

double overlap_error(const Ellipse& a, const Ellipse& b, double normalised_radius, int rows) {
    double factor = normalised_radius / a.equivalent_radius();
    return 1.0 - ellipse_overlap(a.scaled(factor), b.scaled(factor), rows);
}

RepeatabilityResult repeatability(const surf::Keypoints& a, const surf::Keypoints& b, const Eigen::Matrix3d& h_ab,
                                  const cv::Size& size_a, const cv::Size& size_b, const RepeatabilityOptions& options) {
    Eigen::Matrix3d h_ba = h_ab.inverse();
    Visible va = visible_regions(a, h_ab, size_a, size_b, true);
    Visible vb = visible_regions(b, h_ba, size_b, size_a, false);
    RepeatabilityResult result;
    result.visible_a = va.index.size();
    result.visible_b = vb.index.size();
    double min_overlap = 1.0 - options.max_overlap_error;

    std::vector<RegionMatch> pairs;
    for (std::size_t i = 0; i < va.index.size(); ++i) {
        double factor = options.normalised_radius / va.in_a[i].equivalent_radius();
        Ellipse region_a = va.in_a[i].scaled(factor);
        for (std::size_t j = 0; j < vb.index.size(); ++j) {
            Ellipse region_b = vb.in_a[j].scaled(factor);
            if (cannot_overlap(region_a, region_b, min_overlap)) continue;
            double error = 1.0 - ellipse_overlap(region_a, region_b, options.overlap_rows);
            if (error < options.max_overlap_error) pairs.push_back({i, j, error});
        }
    }
    result.correspondences = pairs.size();
    result.matches = greedy_one_to_one(std::move(pairs), va.index.size(), vb.index.size());
    for (auto& m : result.matches) {
        m.a = va.index[m.a];
        m.b = vb.index[m.b];
    }
    std::size_t denominator = std::min(result.visible_a, result.visible_b);
    if (denominator > 0) {
        result.repeatability = static_cast<double>(result.matches.size()) / static_cast<double>(denominator);
    }
    return result;
}

PrecisionResult matching_precision(const surf::Keypoints& a, const surf::Keypoints& b, const Eigen::Matrix3d& h_ab,
                                   const RatioTestOptions& matching, double tolerance) {
    PrecisionResult result;
    result.candidate_pairs = ratio_test_candidates(a, b, matching);
    result.candidates = result.candidate_pairs.size();
    for (const auto& c : result.candidate_pairs) {
        Eigen::Vector2d mapped = apply_homography(h_ab, {a[c.a].x, a[c.a].y});
        double error = (mapped - Eigen::Vector2d(b[c.b].x, b[c.b].y)).norm();
        result.errors.push_back(error);
        if (error <= tolerance) ++result.correct;  // NaN (point sent to infinity) is never correct
    }
    if (result.candidates > 0) {
        result.precision = static_cast<double>(result.correct) / static_cast<double>(result.candidates);
    }
    return result;
}

}  // namespace surfvp::eval
