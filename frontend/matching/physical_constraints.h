// Physical constraints on a junction correspondence (paper section 4.3, eq. 36-37).
//
// Both take the unit segment directions of J (image 1) and J' (image 2), num_segments each, in
// clockwise order, and a cyclic shift k: segment i of J corresponds to segment (i + k) mod N of J'
// (eq. 32 with 0-based indices).
#pragma once

#include <Eigen/Core>

namespace sfm {

// Eq. (36), opaque objects keep the order of the segments: (n_i x n_i+1) (n'_j x n'_j+1) > 0.
// Both junctions being numbered clockwise, their turns add up to 360 degrees and at most one
// exceeds 180 (negative cross product): (36) says that the reflex angle of an ARROW or an L stays
// the reflex angle (a Y and its mirror image both pass). The paper lists 1 <= i < N; we test
// every cyclic neighbour pair (i = N with 1) for N >= 3, so that the result does not depend on
// which segment is numbered first. The two differ only when one junction has a reflex angle and
// the other none (a Y against an ARROW), where the literal test lets one arbitrary shift through.
// A pair whose turn |n_i x n_i+1| or |n'_j x n'_j+1| is below min_sin (near collinear: a T's bar)
// is skipped, its sign being noise.
bool KeepsCyclicOrder(const Eigen::Vector2d* directions, const Eigen::Vector2d* partner_directions,
                      int num_segments, int shift, double min_sin);

// Eq. (37), small rotation between the frames: n_i . n'_j > 0 for every corresponding pair.
bool IsSmallRotation(const Eigen::Vector2d* directions, const Eigen::Vector2d* partner_directions,
                     int num_segments, int shift);

}  // namespace sfm
