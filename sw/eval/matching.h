#pragma once
// Correspondence candidates by descriptor distance alone, paper §IV-A: for each feature of A the
// two nearest descriptors of B (Euclidean, brute force); the nearest is a candidate when its
// distance is below 0.75 of the second's. Optionally only B features within a search radius of
// A's position (the paper's "limited search", 200 px) and of the same Laplacian sign count.
#include <cstddef>
#include <optional>
#include <vector>

#include "sw/surf/keypoint.h"

namespace surfvp::eval {

struct RatioTestOptions {
    double ratio = 0.75;                  // paper §IV-A
    std::optional<double> search_radius;  // px; B features farther than this from A's (x, y) are ignored
    bool same_laplacian = false;          // only B features whose sign equals A's (0 matches only 0)
};

struct Candidate {
    std::size_t a = 0;           // index into A
    std::size_t b = 0;           // index into B: the nearest descriptor
    double distance = 0;         // to the nearest
    double second_distance = 0;  // to the second nearest
};

double descriptor_distance(const surf::Keypoint& a, const surf::Keypoint& b);

// One candidate per A feature at most, in A's order; several A features may name the same B
// feature (the paper asks for no one-to-one step). Ties go to the lower B index, so equal
// nearest and second distances fail the ratio test. An A feature with fewer than two eligible
// B features has no candidate.
std::vector<Candidate> ratio_test_candidates(const surf::Keypoints& a, const surf::Keypoints& b,
                                             const RatioTestOptions& options = {});

}  // namespace surfvp::eval
