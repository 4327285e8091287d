// Where two detected segments' lines meet (paper section 2.2, eq. 6).
#pragma once

#include <optional>

#include <Eigen/Core>

#include "frontend/segments/line_segment.h"

namespace sfm {

// A detected segment in the paper's line form (eq. 1-2), computed once: every point of the line is
// p = rho*q + t*n. Kept beside the end-points so that the pair tests do not renormalise per pair.
struct SegmentLine {
  explicit SegmentLine(const LineSegment& segment);

  Eigen::Vector2d p0, p1;  // detected end-points, pixels
  Eigen::Vector2d n;       // (1) unit direction, p0 -> p1
  Eigen::Vector2d q;       // unit normal, n rotated by +90 degrees
  double rho;              // (2) signed distance of the line from the origin, pixels
  double length;           // |p1 - p0|, pixels
};

// Eq. (6): the point p0 = rho_a*q_a + ((rho_b - rho_a*(q_a.q_b)) / (n_a.q_b)) * n_a common to the
// lines of a and b. Returns nullopt when the lines are within min_angle_rad of parallel: a line
// error sigma then moves p0 by sigma / sin(angle) along the lines, so p0 is no usable location.
std::optional<Eigen::Vector2d> IntersectLines(const SegmentLine& a, const SegmentLine& b,
                                              double min_angle_rad);
// The same with sin(min_angle_rad) given, for callers testing many pairs with one angle.
std::optional<Eigen::Vector2d> IntersectLinesMinSine(const SegmentLine& a, const SegmentLine& b,
                                                     double min_sine);

}  // namespace sfm
