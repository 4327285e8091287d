// Image segments for tests, written as their end-points' coordinates.
#pragma once

#include <Eigen/Core>

#include "frontend/segments/line_segment.h"

namespace sfm::testing {

// The segment from (x0, y0) to (x1, y1), pixels; support and fit left at zero.
inline LineSegment Segment(double x0, double y0, double x1, double y1) {
  LineSegment s;
  s.p0 = Eigen::Vector2d(x0, y0);
  s.p1 = Eigen::Vector2d(x1, y1);
  return s;
}

}  // namespace sfm::testing
