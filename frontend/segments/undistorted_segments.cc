#include "frontend/segments/undistorted_segments.h"

#include <algorithm>
#include <cmath>

namespace sfm {

void ClipSegmentsToStoredView(const Camera& camera, double margin, double min_length,
                              LineSegments* segments) {
  ClipSegmentsToRegion([&](const Eigen::Vector2d& p) { return SeenByStoredImage(camera, p, margin); },
                       min_length, segments);
}

void ClipSegmentsToRegion(const std::function<bool(const Eigen::Vector2d&)>& in_region, double min_length,
                          LineSegments* segments) {
  LineSegments kept;
  kept.reserve(segments->size());
  for (const LineSegment& segment : *segments) {
    const double length = segment.Length();
    const int steps = std::max(1, static_cast<int>(std::ceil(length / 0.5)));
    auto at = [&](double s) -> Eigen::Vector2d { return segment.p0 + s * (segment.p1 - segment.p0); };
    auto seen = [&](double s) { return in_region(at(s)); };
    // Longest run of seen samples, in sample indices [best_first, best_last].
    int best_first = -1, best_last = -2, first = -1;
    bool all_seen = true;
    for (int i = 0; i <= steps; ++i) {
      if (seen(static_cast<double>(i) / steps)) {
        if (first < 0) first = i;
        if (i - first > best_last - best_first) best_first = first, best_last = i;
      } else {
        all_seen = false;
        first = -1;
      }
    }
    if (all_seen) {
      kept.push_back(segment);
      continue;
    }
    if (best_first < 0) continue;
    // Bisection of the crossing between a seen and an unseen sample.
    auto crossing = [&](double inside, double outside) {
      for (int k = 0; k < 20 && std::abs(outside - inside) * length > 1.0 / 64; ++k) {
        const double mid = 0.5 * (inside + outside);
        (seen(mid) ? inside : outside) = mid;
      }
      return inside;
    };
    const double s0 = best_first == 0 ? 0.0
                                      : crossing(static_cast<double>(best_first) / steps,
                                                 static_cast<double>(best_first - 1) / steps);
    const double s1 = best_last == steps ? 1.0
                                         : crossing(static_cast<double>(best_last) / steps,
                                                    static_cast<double>(best_last + 1) / steps);
    if ((s1 - s0) * length < min_length) continue;
    LineSegment clipped = segment;
    clipped.p0 = at(s0);
    clipped.p1 = at(s1);
    clipped.support = static_cast<int>(std::lround(segment.support * (s1 - s0)));
    kept.push_back(clipped);
  }
  *segments = std::move(kept);
}

LineSegments DetectUndistortedSegments(const ImageUndistorter& undistorter, const cv::Mat& stored_image,
                                       const SegmentDetectorOptions& options) {
  LineSegments segments = DetectLineSegments(undistorter.Apply(stored_image), options);
  if (!undistorter.FullView()) return segments;
  const Eigen::Vector2d offset = undistorter.CanvasOffset();
  for (LineSegment& segment : segments) {
    segment.p0 -= offset;
    segment.p1 -= offset;
  }
  ClipSegmentsToStoredView(undistorter.camera(), options.border_margin, options.min_length, &segments);
  return segments;
}

}  // namespace sfm
