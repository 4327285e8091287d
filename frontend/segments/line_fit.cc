#include "frontend/segments/line_fit.h"

#include <algorithm>
#include <cmath>

#include <glog/logging.h>

namespace sfm {

FittedLine LineFitAccumulator::Fit() const {
  CHECK_GE(n_, 2) << "a line fit needs two points";
  return FitImpl</*kWithRms=*/true>();
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
