// The relative poses the images determined, as pose graph constraints (pose_graph.h), from the
// matcher's refinement of each pair (RefinePairGeometry: the MAP pose from the pair's junction
// matches with the odometry as its prior).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "backend/initialization/pose_graph.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/matching/pair_geometry.h"

namespace sfm {

// Why pairs gave no constraint, counted over a run (metrics.json "initialization").
struct VisualConstraintCounts {
  int pairs = 0;
  int constraints = 0;              // refined pairs with information from their matches
  int too_few_matches = 0;          // the first pass found fewer than the refinement needs
  int too_few_inliers = 0;          // no pose fits enough of them
  int inconsistent_with_prior = 0;  // the pose the matches fit lies beyond the odometry's 99 % ellipsoid
  int no_information = 0;           // refined, but the matches add nothing to the prior
};

// The information the matches alone carry about the pose: the posterior's information minus the
// prior's (Laplace approximations of RefinePairGeometry), with the negative eigenvalues that
// rounding leaves set to zero. A monocular pair's is (close to) singular along the translation's
// length, and along the whole translation for a pair without parallax.
Eigen::Matrix<double, 6, 6> InformationFromMatches(const PairGeometry& prior, const PairGeometry& posterior);

// One constraint per pair whose refinement succeeded, for the frame pairs `pairs` whose priors
// (the geometries matching was given) and diagnostics are in the same order.
std::vector<RelativePoseConstraint> VisualConstraints(const std::vector<std::pair<int, int>>& pairs,
                                                      const std::vector<PairGeometry>& priors,
                                                      const std::vector<MatchingDiagnostics>& diagnostics,
                                                      VisualConstraintCounts* counts);

// The relative rotations the matches fit, whether or not the estimate passed the odometry's gate,
// for measuring the odometry's noise (odometry_noise_estimate.h): every pair whose estimate is
// supported by at least the refinement's minimum of inliers. Only the poses are meaningful.
std::vector<RelativePoseConstraint> VisualRotationSamples(const std::vector<std::pair<int, int>>& pairs,
                                                          const std::vector<MatchingDiagnostics>& diagnostics,
                                                          int min_inliers);

}  // namespace sfm
