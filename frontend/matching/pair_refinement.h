// Refinement of a pair's relative pose from its own junction matches, with the odometry pose as a
// prior (not in the paper; docs/matching.md, "Geometric verification and the guided pass").
//
// The odometry pose and its covariance (PairGeometry) are the prior; each match (x1, x2) is a
// measurement of the epipolar geometry through its Sampson distance, whose standard deviation is
// the junction location sigma. The maximum a posteriori pose under a Cauchy loss (robust to the
// wrong matches of a first pass) and its Laplace covariance form the refined PairGeometry, whose
// epipolar band is then set by the location noise instead of the odometry's.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "frontend/matching/matching_options.h"
#include "frontend/matching/pair_geometry.h"

namespace sfm {

// Signed Sampson distance of a correspondence, x2^T F x1 / sqrt(|(F x1)_xy|^2 + |(F^T x2)_xy|^2),
// pixels: the first-order distance of (x1, x2) from the nearest exact correspondence in the joint
// 4-D space, so with independent errors of sigma in each image coordinate it has sigma sigma. 0
// where both lines vanish (both points at the epipoles).
double SampsonDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2);

// MatchJunctions fills these from its MatchingOptions; the defaults are that struct's.
struct PairRefinementSettings {
  // Standard deviation of a junction location per image axis, pixels, > 0.
  double location_sigma_px = MatchingOptions().location_sigma_px;
  // A match supports the estimate when |Sampson distance| <= gate_sigmas times its predicted
  // sigma (location noise and the estimate's own uncertainty). > 0.
  double gate_sigmas = MatchingOptions().refine_gate_sigmas;
  // Fewer supporting matches than this: no estimate (PairRefinement::Outcome::kTooFewInliers).
  int min_inliers = MatchingOptions().refine_min_inliers;
};

struct PairRefinement {
  enum class Outcome {
    kRefined,
    kNoPriorUncertainty,     // the prior covariance is zero: nothing to refine
    kTooFewMatches,          // fewer matches than min_inliers to begin with
    kTooFewInliers,          // fewer than min_inliers within the gate at the estimate
    kInconsistentWithPrior,  // the estimate lies beyond the prior's 99 % ellipsoid
  };
  Outcome outcome = Outcome::kTooFewMatches;
  bool Refined() const { return outcome == Outcome::kRefined; }
  // The prior it started from, and the refined pose with its posterior covariance when Refined()
  // (else the prior unchanged).
  PairGeometry prior;
  PairGeometry geometry;
  // The estimate whatever the outcome (the prior's pose when none was made): for diagnosis of a
  // fallback.
  Pose3 estimate;
  int matches = 0;   // correspondences given
  int inliers = 0;   // within the gate at the estimate
  // Squared Mahalanobis distance of the estimate from the prior pose under the prior covariance,
  // and the chi-square 99 % quantile it was compared with (degrees of freedom: the prior's rank).
  double prior_distance_squared = 0;
  double prior_gate = 0;
  int iterations = 0;  // Gauss-Newton steps taken, over all rounds
  // The unconstrained estimate lay beyond the prior's ellipsoid and the search inside it ran
  // (docs/matching.md, "Refinement fall-backs"); the estimate is its result.
  bool constrained = false;
  // For each correspondence: within the gate at the estimate (empty unless an estimate was made).
  std::vector<bool> inlier;
};

// The chi-square distribution's 99 % quantile for 1..6 degrees of freedom.
double ChiSquare99(int degrees_of_freedom);

// Squared Mahalanobis distance of `pose` from prior.camera2_T_camera1 under prior.covariance (the
// perturbation (omega, dt) of PairGeometry; pseudo-inverse over the directions with variance, as
// RefinePairGeometry's prior_distance_squared) and, when rank is not null, the covariance's rank.
double PriorDistanceSquared(const PairGeometry& prior, const Pose3& pose, int* rank = nullptr);

// The MAP pose of camera2_T_camera1 given the prior (prior.camera2_T_camera1, prior.covariance)
// and correspondences x1[i] <-> x2[i] (pixels, prior.K). x1 and x2 have equal sizes.
PairRefinement RefinePairGeometry(const PairGeometry& prior, const std::vector<Eigen::Vector2d>& x1,
                                  const std::vector<Eigen::Vector2d>& x2, const PairRefinementSettings& settings);

}  // namespace sfm
