// Junction detection from detected line segments (paper section 2.2).
#pragma once

#include "frontend/junctions/junction.h"
#include "frontend/junctions/junction_options.h"
#include "frontend/segments/line_segment.h"

namespace sfm {

// Junctions of one image, ids 0..n-1, strongest first:
// 1. pairs of segments meeting at their eq. (6) point with junction probability >= the threshold
//    (TestPair: L contacts moving two end-points, T contacts an end-point on another segment's
//    interior, X crossings of two interiors, and collinear pieces of one broken line);
// 2. N-junctions by merging: pairs are taken strongest first, and each grows greedily by the
//    segment whose pairs with every member pass, with the largest sum of pair probabilities.
//    A segment end-point joins one junction only; a segment's interior may hold several (a bar
//    with several stems). Location: probability-weighted mean of the pairwise eq. (6) points;
//    score: sum of the pairwise probabilities.
// Junction segments run from the location to the far end-point of each member segment (both
// end-points for a segment crossed at its interior), clockwise, and are typed by ClassifyJunction.
// CHECK-fails on options that fail Check() (a programmer error: check them up front).
Junctions DetectJunctions(const LineSegments& segments, const JunctionDetectorOptions& options);

}  // namespace sfm
