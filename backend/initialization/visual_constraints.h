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
#include "frontend/tracks/tracks.h"

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

// The relative pose the matches x1 <-> x2 (pixels, refinement.geometry.K) alone determine, and its
// covariance: an essential matrix by RANSAC (OpenCV) gives the inliers and the start, then the
// pose is fitted to those inliers (RefinePairGeometry) under a prior kPriorWidening times wider in
// every sigma than the MAP pose `refinement` found with the odometry as its prior, and centred at
// the start. The odometry then only fixes what the matches cannot see (the translation's length;
// all of the translation without parallax): neither it nor a few wrong matches pull the estimate
// along the directions the matches determine only weakly (a tilt traded for a sideways
// translation). Without an essential matrix, the inliers of the MAP pose; with repeated_pattern
// (the pair's matches came from gates recentred on a hypothesis, MatchingDiagnostics::recentred),
// also when the essential matrix's pose lies beyond the 99 % gate of refinement.prior. The
// outcome is the fit's; prior_used (optional) receives the fit's prior.
PairRefinement RelativePoseFromMatches(const PairRefinement& refinement, const std::vector<Eigen::Vector2d>& x1,
                                       const std::vector<Eigen::Vector2d>& x2,
                                       const PairRefinementSettings& settings,
                                       PairGeometry* prior_used = nullptr, bool repeated_pattern = false);

// One constraint per pair whose refinement succeeded: the pose its final matches determine
// (RelativePoseFromMatches; junction locations of frames[frame_a] and frames[frame_b]) with the
// information they carry. `diagnostics` is in the order of `matches`; settings are the matcher's
// refinement settings.
std::vector<RelativePoseConstraint> VisualConstraints(const std::vector<FramePairMatches>& matches,
                                                      const std::vector<Junctions>& frames,
                                                      const std::vector<MatchingDiagnostics>& diagnostics,
                                                      const PairRefinementSettings& settings,
                                                      VisualConstraintCounts* counts);

// The relative rotations the matches fit, whether or not the estimate passed the odometry's gate,
// for measuring the odometry's noise (odometry_noise_estimate.h): every pair whose estimate is
// supported by at least the refinement's minimum of inliers. Only the poses are meaningful.
std::vector<RelativePoseConstraint> VisualRotationSamples(const std::vector<std::pair<int, int>>& pairs,
                                                          const std::vector<MatchingDiagnostics>& diagnostics,
                                                          int min_inliers);

}  // namespace sfm
