// Junctions of a stored frame in K's undistorted pixel frame, for every view ImageUndistorter
// offers: the same-size image, the full-view canvas, or an equidistant lens's perspective
// sub-views (docs/junctions.md, "Wide lenses").
#pragma once

#include <opencv2/core.hpp>

#include "frontend/junctions/junction.h"
#include "frontend/junctions/junction_options.h"
#include "frontend/segments/line_segment.h"
#include "frontend/segments/segment_detector.h"
#include "geometry/image_undistorter.h"

namespace sfm {

// Without sub-views: DetectJunctions(DetectUndistortedSegments(...)), exactly.
// With sub-views (an equidistant lens, full view): in each sub-view, segments (DetectLineSegments,
// cut to the part the stored image sees options.border_margin px inside its border) and junctions
// (DetectJunctions), so that every pixel threshold of both detectors means what it means on a
// pinhole image; a junction is kept by the sub-view whose axis is closest to its ray (one copy in
// the overlaps), and its location and far ends are mapped to K's pixels by the sub-view's
// homography. Ids 0..n-1, strongest first. `segments` (optional): every sub-view's segments in K's
// pixels, concatenated; the junctions' line_segment indices refer to them.
Junctions DetectUndistortedJunctions(const ImageUndistorter& undistorter, const cv::Mat& stored_image,
                                     const SegmentDetectorOptions& segment_options,
                                     const JunctionDetectorOptions& junction_options,
                                     LineSegments* segments = nullptr);

}  // namespace sfm
