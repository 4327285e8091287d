// Branches at free segment ends (fast path): the short side of a corner that the chains lost is
// looked for directly in the gradient field, by an a-contrario test of the gradient's orientation
// along rays from the end-point of a segment that has no other segment's end-point near it
// (docs/segments.md, step 8).
#pragma once

#include <opencv2/core.hpp>

#include "frontend/segments/line_segment.h"
#include "frontend/segments/segment_detector.h"

namespace sfm {

// What a branch search found, for tests and diagnostics.
struct BranchSearchStats {
  int free_ends = 0;       // end-points searched
  double log10_tests = 0;  // log10 of the number of candidate rays the NFA counts
  int accepted = 0;        // branches appended
  int bridges = 0;         // bridges appended (a segment's line continued to a free end)
};

// Appends to `segments` the branches found at their free end-points. gx, gy: the CV_16S Sobel
// derivatives the segments were found on; magnitude: CV_16S |gx| + |gy| (sub-pixel points across
// each branch); low_magnitude, high_magnitude: the edge thresholds in those units (as on a chain,
// a sample counts only at the low one, and a branch needs an edge point at the high one).
// An end-point is free when no other segment's end-point lies within 2 max_gap of it and no other
// segment passes within about a pixel of the points 2..max_gap px beyond it (a T's stem). At a
// free end, a branch is:
//  - a ray from just beyond the end-point (kCornerOffset along the segment), at least
//    kMinBranchAngle from the segment's own direction either way, along which the gradient is
//    aligned with the ray's normal (within 22.5 degrees, one polarity) and reaches the low
//    threshold at consecutive samples 1 px apart (a run ends at two misses in a row), its NFA
//    counted over every (free end, direction, polarity, length) candidate and at most
//    10^options.fast.log10_nfa_max;
//  - not along an existing segment (at most half its samples within about a pixel of one);
//  - a line fitted to the sub-pixel edge points across the ray (most samples give one), whose
//    intersection with the segment's line (the corner) lies within options.max_gap of the
//    end-point and which reaches at least options.min_length from that corner.
// Rays are tried only in the directions of edge pixels near the end (a pruning that the NFA's
// count ignores); at most two branches per end, 45 degrees apart. Branches are not searched for
// branches of their own.
BranchSearchStats AppendBranchSegments(const cv::Mat& gx, const cv::Mat& gy, const cv::Mat& magnitude,
                                       int low_magnitude, int high_magnitude,
                                       const SegmentDetectorOptions& options, LineSegments* segments);

}  // namespace sfm
