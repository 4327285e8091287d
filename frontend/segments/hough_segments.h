// The reference path's line finder: a Hough transform over sub-pixel edge points, then a
// least-squares fit of each peak's line to its supporting edge points, split at gaps (paper
// section 2, [20], [21]).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "frontend/segments/line_segment.h"
#include "frontend/segments/segment_detector.h"
#include "frontend/segments/subpixel_edges.h"

namespace sfm {

// Segments found among `points` of an image of `image_size`, using options.reference,
// options.min_length and options.max_gap. Each edge point supports at most one segment.
//
// Votes: each point votes for the line normals within options.reference.vote_window_deg of its
// gradient direction (the gradient-restricted transform of O'Gorman & Clowes, used by [21]).
// The strongest remaining peak is taken at each step; its supporting points are those within
// gather_distance of the peak's line whose gradient agrees in angle and polarity, fitted by
// orthogonal least squares, re-gathered within fit_distance of the fitted line and re-fitted;
// sorted along the line and split at gaps; the pieces at least min_length long become segments
// and their points withdraw their votes.
LineSegments HoughSegments(const std::vector<EdgePoint>& points, cv::Size image_size,
                           const SegmentDetectorOptions& options);

}  // namespace sfm
