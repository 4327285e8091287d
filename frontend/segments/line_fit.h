// Orthogonal least-squares line fit with sums kept incrementally (the sub-pixel fit of paper
// section 2 [20]: line parameters from all supporting edge points, end-points from the last ones).
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "frontend/segments/line_segment.h"

namespace sfm {

// A fitted infinite line: a point on it (the centroid of the fitted points) and a unit direction.
struct FittedLine {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();  // pixels
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
  double rms = 0;  // RMS perpendicular distance of the fitted points, pixels

  // Signed perpendicular distance of p to the line, pixels (positive to the left of direction
  // in image axes, i.e. along (-direction.y, direction.x)).
  double Distance(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d d = p - centroid;
    return direction.x() * d.y() - direction.y() * d.x();
  }
  // Orthogonal projection of p onto the line.
  Eigen::Vector2d Project(const Eigen::Vector2d& p) const {
    return centroid + direction * direction.dot(p - centroid);
  }
};

// Sums of points for an orthogonal (total) least-squares fit. Coordinates are taken relative to the
// first point added so that the second moments keep their precision far from the image origin.
class LineFitAccumulator {
 public:
  void Add(double x, double y) {
    if (n_ == 0) {
      ox_ = x;
      oy_ = y;
    }
    x -= ox_;
    y -= oy_;
    ++n_;
    sx_ += x;
    sy_ += y;
    sxx_ += x * x;
    sxy_ += x * y;
    syy_ += y * y;
  }
  void Add(const Eigen::Vector2d& p) { Add(p.x(), p.y()); }
  // Takes back a point added before (the sums are exact up to rounding; the origin stays).
  void Remove(const Eigen::Vector2d& p) {
    const double x = p.x() - ox_, y = p.y() - oy_;
    --n_;
    sx_ -= x;
    sy_ -= y;
    sxx_ -= x * x;
    sxy_ -= x * y;
    syy_ -= y * y;
  }
  // Adds all the points of `other`, as if each had been added here.
  void Merge(const LineFitAccumulator& other);
  int count() const { return n_; }

  // The line minimising the sum of squared perpendicular distances: it passes through the centroid
  // along the principal axis of the scatter matrix. Needs count() >= 2.
  FittedLine Fit() const;
  // Fit()'s centroid and direction, bit for bit, without the RMS (left 0) and without the count
  // check: for the tests after every added point (the fast path's chain splitting) and wherever
  // else only the line is used. There the call, the check and the RMS's square root were a
  // measurable share of the detector's time. Inline, so that the caller's next test overlaps it.
  // (Both run the same FitImpl; the build contracts no multiply-adds, having no -march with FMA.)
  FittedLine FitWithoutRms() const { return FitImpl</*kWithRms=*/false>(); }

 private:
  // Principal axis of [[cxx cxy] [cxy cyy]]: with h = (cxx - cyy) / 2 and r = hypot(h, cxy), the
  // larger eigenvalue's eigenvector is (h + r, cxy), or equivalently (cxy, r - h), whichever is the
  // better conditioned; the smaller eigenvalue is the mean squared perpendicular distance.
  template <bool kWithRms>
  FittedLine FitImpl() const {
    const double mx = sx_ / n_, my = sy_ / n_;
    const double cxx = sxx_ / n_ - mx * mx;
    const double cxy = sxy_ / n_ - mx * my;
    const double cyy = syy_ / n_ - my * my;
    const double h = 0.5 * (cxx - cyy);
    const double root = std::sqrt(h * h + cxy * cxy);
    Eigen::Vector2d axis = h >= 0 ? Eigen::Vector2d(h + root, cxy) : Eigen::Vector2d(cxy, root - h);
    const double norm = axis.norm();
    FittedLine line;
    line.centroid = Eigen::Vector2d(mx + ox_, my + oy_);
    line.direction = norm > 0 ? Eigen::Vector2d(axis / norm) : Eigen::Vector2d(1, 0);
    if (kWithRms) line.rms = std::sqrt(std::max(0.0, 0.5 * (cxx + cyy) - root));
    return line;
  }

  int n_ = 0;
  double ox_ = 0, oy_ = 0;
  double sx_ = 0, sy_ = 0, sxx_ = 0, sxy_ = 0, syy_ = 0;
};

// The segment of `line` between the projections of the two extreme points `first` and `last`
// (paper section 2: end-points are the projections of the last edge pixels onto the fitted line).
LineSegment SegmentOnLine(const FittedLine& line, const Eigen::Vector2d& first, const Eigen::Vector2d& last,
                          int support);

}  // namespace sfm
