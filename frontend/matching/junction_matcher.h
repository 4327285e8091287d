// Junction matching between two frames (paper section 4): the entry point of sfm_matching.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "frontend/junctions/junction.h"
#include "frontend/matching/matching_options.h"
#include "frontend/matching/matching_rule.h"
#include "frontend/matching/pair_geometry.h"
#include "frontend/matching/pair_refinement.h"

namespace sfm {

// Matches junctions a (image 1) with junctions b (image 2), x2^T F x1 = 0 (F from calibration and
// odometry, undistorted pixels): rho (34) for the P x Q pairs (pairs with different segment counts
// or farther than R from each other's epipolar line rejected first), sigma (section 4.2) on the
// topology graphs where options.use_topology, then rule (38) both ways. Matches come in increasing
// index_a. options must pass Check() (CHECKed); the graphs must describe a and b.
std::vector<JunctionMatch> MatchJunctions(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                         const TopologyGraph& graph_b, const Eigen::Matrix3d& F,
                                         const MatchingOptions& options);

// What the PairGeometry overload did, for diagnosis and the benchmark.
struct MatchingDiagnostics {
  int first_pass_matches = 0;
  // Filled when options.refine_geometry; refinement.Refined() says whether the guided pass ran.
  PairRefinement refinement;
  // Partial matches the guided pass added.
  int partial_matches = 0;
  // The matches are a pass of GuidedPassOrHypotheses with the gates centred on a hypothesis; the
  // other fields are that pass's, but `refinement` is of its final matches under the odometry.
  bool recentred = false;
};

// The same with the pair's relative pose and its uncertainty (PairGeometryFromOdometry): F =
// geometry.Fundamental(), and in place of the fixed R each pair's band is options.band_sigmas times
// the spread of its epipolar distances under the pose covariance and the location noise; pairs
// that triangulate behind either camera are rejected (options.use_cheirality). The pipeline's call.
// With options.refine_geometry, the pose is then refined from these matches (RefinePairGeometry,
// the odometry as prior) and the matching runs again with the refined pose and its covariance in a
// band of options.refine_gate_sigmas: the result of that guided pass is returned, or the first
// pass's when the refinement falls back. The guided pass then adds
// partial matches (JunctionMatch::Partial, k against k + 1 segments) among the junctions it left
// unmatched. diagnostics may be null.
std::vector<JunctionMatch> MatchJunctions(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                         const TopologyGraph& graph_b, const PairGeometry& geometry,
                                         const MatchingOptions& options, MatchingDiagnostics* diagnostics = nullptr);

// MatchJunctions in its two steps, so that a caller can look at every pair's verified pose before
// the guided passes run (the pipeline measures the odometry's noise from them and matches again
// with wider gates when it is larger than declared): VerifiedFirstPass returns the first pass's
// matches and fills diagnostics' first_pass_matches and refinement; GuidedPass takes those matches
// and diagnostics and returns MatchJunctions' result. diagnostics must not be null.
std::vector<JunctionMatch> VerifiedFirstPass(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                             const TopologyGraph& graph_b, const PairGeometry& geometry,
                                             const MatchingOptions& options, MatchingDiagnostics* diagnostics);
std::vector<JunctionMatch> GuidedPass(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                      const TopologyGraph& graph_b, std::vector<JunctionMatch> first,
                                      const MatchingOptions& options, MatchingDiagnostics* diagnostics);

constexpr double kDisagreementBands = 2;

// Whether `hypothesis` disputes the verified pose about where the first pass's verified inliers
// (x1[k] <-> x2[k], verified.inlier[k]) go: each inlier's point, at its depth under the verified
// pose, moved into camera 2 by the hypothesis (its translation scaled to the verified pose's, which
// two images cannot tell), lands more than kDisagreementBands guided bands,
// refine_gate_sigmas * location_sigma_px, from x2 at the median. Not the epipolar distance: a
// repeated pattern matched one period off under a wrong pose fits the right pose's epipolar lines
// too (the shift runs along them; entry-P10 at 3x, docs/real_results.md). True when the pose was
// not verified or no inlier has a depth in front of camera 1.
bool HypothesisDisputed(const Pose3& hypothesis, const PairRefinement& verified, const std::vector<Eigen::Vector2d>& x1,
                        const std::vector<Eigen::Vector2d>& x2, const MatchingOptions& options);

// GuidedPass, then each hypothesis that disputes the verified pose (HypothesisDisputed): the two
// steps again with the gates centred on it (geometry's covariance). Such a pass replaces the best
// so far, n matches, when it has kHypothesisMatchRatio n and n + kHypothesisExcessSigmas sqrt(n)
// (the count's own spread is about sqrt(n) at either centre), and its matches refine under
// geometry's own prior (the odometry, which also picks between the two poses a near-planar scene
// allows); its matches and that refinement are returned, and diagnostics->recentred is set
// (docs/matching.md, "Pose hypotheses").
constexpr double kHypothesisMatchRatio = 1.2;
constexpr double kHypothesisExcessSigmas = 3;
std::vector<JunctionMatch> GuidedPassOrHypotheses(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                                  const TopologyGraph& graph_b, std::vector<JunctionMatch> first,
                                                  const PairGeometry& geometry,
                                                  const std::vector<Pose3>& hypotheses,
                                                  const MatchingOptions& options, MatchingDiagnostics* diagnostics);

// Whether the median of `matches` (a pair's, a's junctions against b's) lies more than
// kDisagreementBands guided bands from the epipolar lines of geometry's pose; false without
// matches. The test of a pair's matches against a refined trajectory (docs/matching.md,
// "Matching again after the adjustment").
bool MatchesDisagree(const Junctions& a, const Junctions& b, const std::vector<JunctionMatch>& matches,
                     const PairGeometry& geometry, const MatchingOptions& options);

// The settings of the refinement MatchJunctions runs (RefinePairGeometry), from options.
PairRefinementSettings RefinementSettings(const MatchingOptions& options);

}  // namespace sfm
