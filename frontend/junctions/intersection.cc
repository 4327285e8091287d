#include "frontend/junctions/intersection.h"

#include <cmath>

namespace sfm {

SegmentLine::SegmentLine(const LineSegment& segment)
    : p0(segment.p0),
      p1(segment.p1),
      n(segment.Direction()),
      q(segment.Normal()),
      rho(segment.Rho()),
      length(segment.Length()) {}

std::optional<Eigen::Vector2d> IntersectLines(const SegmentLine& a, const SegmentLine& b,
                                              double min_angle_rad) {
  return IntersectLinesMinSine(a, b, std::sin(min_angle_rad));
}

std::optional<Eigen::Vector2d> IntersectLinesMinSine(const SegmentLine& a, const SegmentLine& b,
                                                     double min_sine) {
  // n_a.q_b is the sine of the angle between the lines.
  const double sine = a.n.dot(b.q);
  if (!(std::abs(sine) >= min_sine)) return std::nullopt;
  return Eigen::Vector2d(a.rho * a.q + ((b.rho - a.rho * a.q.dot(b.q)) / sine) * a.n);
}

}  // namespace sfm
