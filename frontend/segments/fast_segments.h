// The fast path: one Sobel pass, anchored edge chaining, chains split into straight pieces by
// incremental least squares, and an a-contrario check of each piece (after EDLines, Akinlar &
// Topal 2011, with sub-pixel edge points as in the reference path).
#pragma once

#include <opencv2/core.hpp>

#include "frontend/segments/line_segment.h"
#include "frontend/segments/segment_detector.h"

namespace sfm {

// Segments of an 8-bit single-channel image, using options.fast, the edge contrast thresholds and
// options.min_length. Steps:
//  1. Gaussian pre-smoothing (options.fast.presmooth_sigma), then one 3x3 Sobel pass.
//  2. Anchors: pixels above the high threshold that are maxima of |gx|+|gy| across the edge.
//  3. From each anchor not yet on a chain, walk both ways along the edge, each step to the
//     strongest of the three pixels ahead, while above the low threshold (ED's routing).
//  4. Each chain pixel is moved to the sub-pixel maximum of the gradient across the edge.
//  5. A line grows along the chain while its next point lies within options.fast.line_tolerance
//     of the least-squares line; then a new line starts (EDLines' splitting).
//  6. A piece is kept if it is long enough and its NFA (gradient alignment along the whole
//     segment, precision 1/8) is small enough; end-points are the projections of its first and
//     last edge points.
LineSegments DetectFastSegments(const cv::Mat& grey, const SegmentDetectorOptions& options);

}  // namespace sfm
