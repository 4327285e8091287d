// Joining straight pieces of edge chains that continue each other across a short gap (the fast
// path's counterpart of the reference path's gap rule: a line is split only at gaps > max_gap).
// Chains end where they run into another chain or where the gradient dips for a pixel or two, so
// one straight edge often arrives as two or more pieces.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "frontend/segments/line_fit.h"

namespace sfm {

struct LinePiece {
  LineFitAccumulator fit;                                 // sums of its sub-pixel edge points
  Eigen::Vector2d first = Eigen::Vector2d::Zero();        // its first edge point, pixels
  Eigen::Vector2d last = Eigen::Vector2d::Zero();         // its last edge point, pixels
  Eigen::Vector2d gradient_sum = Eigen::Vector2d::Zero();  // sum of the image gradient over its points
  bool merged_away = false;                               // true once joined into another piece
  // For a piece between two long pieces of the same chain (a short side between two corners): its
  // length between the intersections of its line with theirs. Pixels; 0 otherwise (and for a
  // joined piece).
  double corner_length = 0;
};

// Joins pairs of pieces of the same polarity with end-points at most `max_gap` pixels apart when
// the line fitted to the union of their edge points passes within `tolerance` pixels of all four
// end-points, until no pair joins. End-points here are the projections of first and last on the
// piece's own fitted line. A joined piece keeps the two outermost first/last points.
void MergeCollinearPieces(double max_gap, double tolerance, std::vector<LinePiece>* pieces);

}  // namespace sfm
