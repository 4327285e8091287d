// The local depth range test of the guided pass (not in the paper; docs/matching.md, "The local
// depth range"). The epipolar band only says where along the line a partner may lie sideways; along
// the line, any depth in front of both cameras passes. The pair's verified matches (the inliers of
// RefinePairGeometry) say more: their inverse depths under the refined pose. On a plane the inverse
// depth is an affine function of the normalised image position, so a point of a piecewise planar
// scene surrounded by verified points of its surface has an inverse depth inside their range, and at
// an occlusion edge the neighbours of both surfaces span both depths. A candidate partner whose
// depth lies outside the range of the nearest verified matches around it (beyond the location
// noise) is rejected: in the VGG corridor these are wrong partners far along the epipolar line of a
// junction near the focus of expansion (docs/matching_results.md, "The local depth range").
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "frontend/matching/pair_geometry.h"

namespace sfm {

// Inverse depth q = 1/Z (Z: depth in camera 1, in the units of geometry's translation) of the
// point on the ray of x1 whose image in camera 2 lies at `parallax` pixels beyond v2 along the
// epipolar line (ParallaxFrameOf): q = s ray_z / (1 - s t_z), s = parallax / scale. +infinity when
// the point would lie at or behind camera 2's centre plane (1 - s t_z <= 0). frame.tested required.
double InverseDepthOfParallax(const ParallaxFrame& frame, double t_z, double parallax);
// Its inverse: the parallax (pixels) of inverse depth q; +infinity when ray_z + q t_z <= 0.
double ParallaxOfInverseDepth(const ParallaxFrame& frame, double t_z, double q);

class LocalDepthRange {
 public:
  // geometry: the (refined) pair geometry. x1[k] <-> x2[k]: the verified correspondences, x1[k]
  // being junction source_a[k] of image 1 (so that a junction is not its own neighbour).
  // locations_a: the locations of all junctions of image 1 to be tested. neighbours: how many of
  // the nearest verified correspondences (in image 1) set a junction's range, >= 1. The tolerance
  // is gate_sigmas * sqrt(sigma_v^2 + 2 location_sigma_px^2) pixels along the line, as the
  // cheirality test's (sigma_v: the spread of v2 under the pose covariance). screen_verified: first
  // drop the verified correspondences that fail the same test against the other verified ones.
  LocalDepthRange(const PairGeometry& geometry, const std::vector<Eigen::Vector2d>& x1,
                  const std::vector<Eigen::Vector2d>& x2, const std::vector<int>& source_a,
                  const std::vector<Eigen::Vector2d>& locations_a, int neighbours, double gate_sigmas,
                  double location_sigma_px, bool screen_verified = true);

  // Whether x2 may be the partner of junction index_a: its parallax lies within the interval of
  // the neighbours' inverse depths widened by the tolerance. True where no test applies (the ray
  // of the junction untested by ParallaxFrameOf, or no usable neighbour).
  bool Passes(int index_a, const Eigen::Vector2d& x2) const;

  // The allowed parallax interval of junction index_a, pixels (lo > hi: untested).
  struct Interval {
    bool tested = false;
    double lo = 0, hi = 0;
  };
  // Computed on first use (the guided pass asks only for junctions with candidates); not thread safe.
  const Interval& IntervalOf(int index_a) const;

 private:
  // The inverse-depth range of the neighbours_ verified correspondences nearest to p in image 1,
  // those of junction exclude_source left out; false when there are none.
  bool NeighbourRange(const Eigen::Vector2d& p, int exclude_source, double* q_low, double* q_high) const;

  struct Verified {
    Eigen::Vector2d x1;
    int source = -1;
    double q = 0;
    int own = -1;  // index of its frame and parallax in the constructor's list
  };
  PairGeometry geometry_;
  // Buckets verified_ into a uniform grid over its bounding box (verified_ reordered by cell).
  void BuildGrid();
  int CellOf(const Eigen::Vector2d& x) const;  // clamped to the grid

  std::vector<Verified> verified_;  // ordered by grid cell
  Eigen::Vector2d grid_origin_ = Eigen::Vector2d::Zero();
  double cell_size_ = 1;
  int grid_columns_ = 0, grid_rows_ = 0;
  std::vector<size_t> cell_start_;  // verified_[cell_start_[c], cell_start_[c + 1]) lie in cell c
  std::vector<Eigen::Vector2d> locations_a_;
  size_t neighbours_ = 0;
  double gate_sigmas_ = 0, location_sigma_px_ = 0;
  mutable std::vector<char> computed_;
  mutable std::vector<ParallaxFrame> frames_;
  mutable std::vector<Interval> intervals_;
  mutable std::vector<std::pair<double, double>> nearest_;  // scratch of IntervalOf
};

}  // namespace sfm
