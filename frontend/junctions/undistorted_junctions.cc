#include "frontend/junctions/undistorted_junctions.h"

#include <algorithm>
#include <utility>

#include "frontend/junctions/junction_detector.h"
#include "frontend/segments/undistorted_segments.h"

namespace sfm {

Junctions DetectUndistortedJunctions(const ImageUndistorter& undistorter, const cv::Mat& stored_image,
                                     const SegmentDetectorOptions& segment_options,
                                     const JunctionDetectorOptions& junction_options, LineSegments* segments) {
  if (undistorter.SubViews().empty()) {
    LineSegments found = DetectUndistortedSegments(undistorter, stored_image, segment_options);
    Junctions junctions = DetectJunctions(found, junction_options);
    if (segments != nullptr) *segments = std::move(found);
    return junctions;
  }
  const double margin = segment_options.border_margin;
  Junctions junctions;
  LineSegments all_segments;
  for (int k = 0; k < static_cast<int>(undistorter.SubViews().size()); ++k) {
    const PerspectiveSubView& view = undistorter.SubViews()[k];
    LineSegments found = DetectLineSegments(undistorter.ApplySubView(k, stored_image), segment_options);
    ClipSegmentsToRegion([&](const Eigen::Vector2d& p) { return undistorter.SubViewSees(k, p, margin); },
        segment_options.min_length, &found);
    const int first_segment = static_cast<int>(all_segments.size());
    for (Junction& junction : DetectJunctions(found, junction_options)) {
      if (undistorter.SubViewOf(view.Ray(junction.location)) != k) continue;
      junction.location = view.ToUndistorted(junction.location);
      for (JunctionSegment& segment : junction.segments) {
        segment.end = view.ToUndistorted(segment.end);
        if (segment.line_segment >= 0) segment.line_segment += first_segment;
      }
      junctions.push_back(std::move(junction));
    }
    for (LineSegment& segment : found) {
      segment.p0 = view.ToUndistorted(segment.p0);
      segment.p1 = view.ToUndistorted(segment.p1);
      all_segments.push_back(segment);
    }
  }
  std::stable_sort(junctions.begin(), junctions.end(),
                   [](const Junction& a, const Junction& b) { return a.score > b.score; });
  for (int i = 0; i < static_cast<int>(junctions.size()); ++i) junctions[i].id = i;
  if (segments != nullptr) *segments = std::move(all_segments);
  return junctions;
}

}  // namespace sfm
