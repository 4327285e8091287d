// Segments of a stored frame in K's pixel frame, found on the undistorted image of either view
// (same size, or the full-view canvas of ImageUndistorter; docs/segments.md).
#pragma once

#include <functional>
#include <opencv2/core.hpp>

#include "geometry/camera.h"
#include "geometry/image_undistorter.h"
#include "frontend/segments/line_segment.h"
#include "frontend/segments/segment_detector.h"

namespace sfm {

// DetectLineSegments on undistorter.Apply(stored_image). With a full-view canvas the segments are
// moved back to K's pixel frame (x - left, y - top; they may then lie outside [0, width) x
// [0, height)) and clipped to the part the stored image sees (ClipSegmentsToStoredView with
// options.border_margin; also when a pincushion lens's canvas is the image itself). Without a full
// view (or without distortion): exactly DetectLineSegments of the undistorted image.
LineSegments DetectUndistortedSegments(const ImageUndistorter& undistorter, const cv::Mat& stored_image,
                                       const SegmentDetectorOptions& options);

// Cuts each segment (K's pixel frame) to its longest piece whose points the stored image sees at
// least `margin` px inside its border (SeenByStoredImage), end-points found to 1/64 px by bisection
// between 0.5 px samples; drops a segment whose piece is shorter than `min_length` (its support
// scaled by the share kept). A segment wholly inside is left bit for bit as it was. This is what
// DropBorderSegments does at an image border, for the curved border of the seen region.
void ClipSegmentsToStoredView(const Camera& camera, double margin, double min_length, LineSegments* segments);
// The same cut for any region given by `seen` (a pixel of the segments' frame -> inside or not).
void ClipSegmentsToRegion(const std::function<bool(const Eigen::Vector2d&)>& seen, double min_length,
                          LineSegments* segments);

}  // namespace sfm
