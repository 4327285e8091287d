#include "frontend/segments/line_fit.h"

#include <algorithm>
#include <cmath>

#include <glog/logging.h>

namespace sfm {

FittedLine LineFitAccumulator::Fit() const {
  CHECK_GE(n_, 2) << "a line fit needs two points";
  const double mx = sx_ / n_, my = sy_ / n_;
  const double cxx = sxx_ / n_ - mx * mx;
  const double cxy = sxy_ / n_ - mx * my;
  const double cyy = syy_ / n_ - my * my;
  // Principal axis of [[cxx cxy] [cxy cyy]]: with h = (cxx - cyy) / 2 and r = hypot(h, cxy), the
  // larger eigenvalue's eigenvector is (h + r, cxy), or equivalently (cxy, r - h), whichever is the
  // better conditioned; the smaller eigenvalue is the mean squared perpendicular distance.
  const double h = 0.5 * (cxx - cyy);
  const double root = std::sqrt(h * h + cxy * cxy);
  Eigen::Vector2d axis = h >= 0 ? Eigen::Vector2d(h + root, cxy) : Eigen::Vector2d(cxy, root - h);
  const double norm = axis.norm();
  FittedLine line;
  line.centroid = Eigen::Vector2d(mx + ox_, my + oy_);
  line.direction = norm > 0 ? Eigen::Vector2d(axis / norm) : Eigen::Vector2d(1, 0);
  line.rms = std::sqrt(std::max(0.0, 0.5 * (cxx + cyy) - root));
  return line;
}

void LineFitAccumulator::Merge(const LineFitAccumulator& other) {
  if (other.n_ == 0) return;
  if (n_ == 0) {
    *this = other;
    return;
  }
  // other's coordinates are relative to its origin: shift them by d to ours.
  const double dx = other.ox_ - ox_, dy = other.oy_ - oy_, m = other.n_;
  sxx_ += other.sxx_ + 2 * dx * other.sx_ + m * dx * dx;
  sxy_ += other.sxy_ + dx * other.sy_ + dy * other.sx_ + m * dx * dy;
  syy_ += other.syy_ + 2 * dy * other.sy_ + m * dy * dy;
  sx_ += other.sx_ + m * dx;
  sy_ += other.sy_ + m * dy;
  n_ += other.n_;
}

LineSegment SegmentOnLine(const FittedLine& line, const Eigen::Vector2d& first, const Eigen::Vector2d& last,
                          int support) {
  LineSegment segment;
  segment.p0 = line.Project(first);
  segment.p1 = line.Project(last);
  segment.support = support;
  segment.fit_rms = line.rms;
  return segment;
}

}  // namespace sfm
