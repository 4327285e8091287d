// LineSegment: a straight image segment with sub-pixel line parameters (paper section 2, eq. 1-2).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace sfm {

struct LineSegment {
  Eigen::Vector2d p0 = Eigen::Vector2d::Zero();  // end-point, pixels
  Eigen::Vector2d p1 = Eigen::Vector2d::Zero();  // other end-point, pixels
  int support = 0;        // number of edge pixels the line was fitted to
  double fit_rms = 0;     // RMS perpendicular distance of those pixels to the line, pixels

  double Length() const { return (p1 - p0).norm(); }
  // (1) unit direction n = (p1 - p0) / |p1 - p0|.
  Eigen::Vector2d Direction() const { return (p1 - p0).normalized(); }
  // Unit normal q: n rotated by +90 degrees in pixel axes, q = (-n.y, n.x).
  Eigen::Vector2d Normal() const {
    const Eigen::Vector2d n = Direction();
    return Eigen::Vector2d(-n.y(), n.x());
  }
  // (2) signed distance rho of the line from the origin: every point is p = rho*q + t*n.
  double Rho() const { return Normal().dot(p0); }
  // Position t of a point's projection along the line, measured from the foot of the origin.
  double T(const Eigen::Vector2d& p) const { return Direction().dot(p); }
};

using LineSegments = std::vector<LineSegment>;

}  // namespace sfm
