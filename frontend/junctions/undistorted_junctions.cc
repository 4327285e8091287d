#include "frontend/junctions/undistorted_junctions.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "frontend/junctions/junction_detector.h"
#include "frontend/segments/undistorted_segments.h"

namespace sfm {
namespace {

// A detected segment of one sub-view, as the rays of its end-points (camera frame, unit).
struct SegmentRays {
  int view = -1;
  Eigen::Vector3d ends[2];
};

int Root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Segments of two sub-views that are one image line where the views overlap: they overlap along
// the line by at least min_overlap (radians), and each end-point lying within the other's extent
// is within tolerance (radians) of the other's plane through the camera centre. A line crossing
// from one sub-view's cell into the next is then one line of the topology graph (section 4.2), as
// on a single image.
bool OneImageLine(const SegmentRays& a, const SegmentRays& b, double tolerance, double min_overlap) {
  const Eigen::Vector3d normal_a = a.ends[0].cross(a.ends[1]).normalized();
  const Eigen::Vector3d normal_b = b.ends[0].cross(b.ends[1]).normalized();
  // Angle along a's great circle from a's first end, towards its second.
  const Eigen::Vector3d along = normal_a.cross(a.ends[0]);
  auto angle = [&](const Eigen::Vector3d& r) { return std::atan2(r.dot(along), r.dot(a.ends[0])); };
  const double a_end = angle(a.ends[1]);
  double b_lo = angle(b.ends[0]), b_hi = angle(b.ends[1]);
  if (b_lo > b_hi) std::swap(b_lo, b_hi);
  if (std::min(a_end, b_hi) - std::max(0.0, b_lo) < min_overlap) return false;
  for (int e = 0; e < 2; ++e) {
    const double t = angle(b.ends[e]);
    if (t >= 0 && t <= a_end && std::abs(normal_a.dot(b.ends[e])) > tolerance) return false;
    const double u = angle(a.ends[e]);
    if (u >= b_lo && u <= b_hi && std::abs(normal_b.dot(a.ends[e])) > tolerance) return false;
  }
  return true;
}

}  // namespace

Junctions DetectUndistortedJunctions(const ImageUndistorter& undistorter, const cv::Mat& stored_image,
                                     const SegmentDetectorOptions& segment_options,
                                     const JunctionDetectorOptions& junction_options,
                                     LineSegments* segments) {
  if (undistorter.SubViews().empty()) {
    LineSegments found = DetectUndistortedSegments(undistorter, stored_image, segment_options);
    Junctions junctions = DetectJunctions(found, junction_options);
    if (segments != nullptr) *segments = std::move(found);
    return junctions;
  }
  const Camera& camera = undistorter.camera();
  const double margin = segment_options.border_margin;
  Junctions junctions;
  LineSegments all_segments;
  std::vector<SegmentRays> rays;
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
      rays.push_back({k, {view.Ray(segment.p0), view.Ray(segment.p1)}});
      segment.p0 = view.ToUndistorted(segment.p0);
      segment.p1 = view.ToUndistorted(segment.p1);
      all_segments.push_back(segment);
    }
  }
  // The junctions' segments seen by two sub-views: one line index (the smaller).
  std::vector<int> used;
  for (const Junction& junction : junctions) {
    for (const JunctionSegment& segment : junction.segments) {
      if (segment.line_segment >= 0) used.push_back(segment.line_segment);
    }
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<int> parent(all_segments.size());
  for (int i = 0; i < static_cast<int>(parent.size()); ++i) parent[i] = i;
  const double focal = std::max(camera.fx, camera.fy);
  const double tolerance = junction_options.collinear_max_offset_px / focal;
  const double min_overlap = segment_options.min_length / focal;
  for (size_t i = 0; i < used.size(); ++i) {
    for (size_t j = i + 1; j < used.size(); ++j) {
      const SegmentRays &a = rays[used[i]], &b = rays[used[j]];
      if (a.view == b.view || !OneImageLine(a, b, tolerance, min_overlap)) continue;
      const int ra = Root(parent, used[i]), rb = Root(parent, used[j]);
      parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  for (Junction& junction : junctions) {
    for (JunctionSegment& segment : junction.segments) {
      if (segment.line_segment >= 0) segment.line_segment = Root(parent, segment.line_segment);
    }
  }
  std::stable_sort(junctions.begin(), junctions.end(),
                   [](const Junction& a, const Junction& b) { return a.score > b.score; });
  for (int i = 0; i < static_cast<int>(junctions.size()); ++i) junctions[i].id = i;
  if (segments != nullptr) *segments = std::move(all_segments);
  return junctions;
}

}  // namespace sfm
