// Settings of junction matching (paper section 4). docs/matching.md says how each default was chosen.
#pragma once

#include <cmath>
#include <string>

#include "frontend/segments/endpoint_model.h"
#include "util/status.h"

namespace sfm {

// The two forms of rho1 in section 4.1.
enum class Rho1Kind {
  kExponential,  // eq. (31): 0.5*(exp(-w d) + exp(-w d')), exp(-w R) = 0.01
  kLinear,       // footnote 10: 0.5*(2 - (d + d')/R), more tolerant of a poor epipolar geometry
};

struct MatchingOptions {
  // R of section 4.1: largest distance of a junction location from the epipolar line of its
  // partner's location; a pair farther than this either way is unmatched. Pixels.
  double max_epipolar_distance_px = 10.0;
  // tau1 of (38): a candidate pair needs a similarity above this. Unitless, >= 0.
  double tau1 = 0.0;
  // tau2 of (38): the chosen partner must beat every other candidate, both ways, by more than
  // this. Unitless, >= 0.
  double tau2 = 0.1;
  Rho1Kind rho1_kind = Rho1Kind::kLinear;
  // true: rule (38) on sigma (section 4.2, junction topology); false: on plain rho (34).
  bool use_topology = true;
  // f(t) of eq. (5), t = detected minus true end-point along the outward direction (eq. 8),
  // pixels. Use the model junction detection uses.
  EndpointModel endpoint_model;
  // The epipolar line of an end-point counts as parallel to the partner segment (section 3.2, last
  // paragraph) when, along the partner's length, it departs from the partner's line by at most
  // this; nearer parallel than that the intersection p'e is set by noise. Pixels, > 0.
  double parallel_tolerance_px = 1.0;
  // (36) compares the turn from segment i to segment i+1 in both junctions; a pair of segments
  // closer than this to collinear (the two halves of a T's bar) has no reliable turn and is not
  // tested. Degrees, in [0, 45).
  double cyclic_order_min_angle_deg = 5.0;

  // Used only when MatchJunctions is given the pair's pose and its uncertainty (PairGeometry).
  // use_pose_band: the search band of each pair replaces R (false: R as without the pose): band_sigmas * sqrt(sigma_pose^2 + 2
  // location_sigma_px^2) in each image, sigma_pose the spread of that epipolar distance under the
  // pose covariance at the two locations (and rho1 uses d / band in place of d / R). Unitless, > 0.
  bool use_pose_band = true;
  double band_sigmas = 3.0;
  // Standard deviation of a junction location, pixels, >= 0 (band and cheirality tolerance).
  double location_sigma_px = 0.5;
  // Reject pairs whose triangulation lies behind camera 1 or 2 by more than band_sigmas of the
  // parallax's uncertainty (PassesCheirality).
  bool use_cheirality = true;

  // Geometric verification and the guided second pass (PairGeometry overload only; docs/matching.md,
  // "Geometric verification and the guided pass"): the pair's pose is re-estimated from the first
  // pass's matches with the odometry as its prior (RefinePairGeometry), then rule (38) runs again
  // with the refined pose and its posterior covariance, in a band of refine_gate_sigmas (in place of
  // band_sigmas). Falls back to the first pass when fewer than refine_min_inliers matches lie within
  // that gate at the estimate, or the estimate is outside the prior's chi-square 99 % ellipsoid.
  bool refine_geometry = true;
  // sqrt of the chi-square 99 % quantile with one degree of freedom: a 99 % gate on one distance.
  double refine_gate_sigmas = 2.576;
  // Three matches per degree of freedom of an epipolar geometry (5).
  int refine_min_inliers = 15;
  // When the refined pose lies beyond the prior's 99 % ellipsoid, take the MAP pose inside it before
  // falling back (PairRefinementSettings::constrain_to_prior_gate; docs/matching.md, "Refinement
  // fall-backs"; it changes nothing where the unconstrained estimate passes, i.e. on every pair of
  // the default benchmarks, and refines the VGG pairs that fell back after a change of the junctions).
  bool refine_constrain_to_prior_gate = true;
  // The local depth range test in the guided pass (docs/matching.md, "The local depth range"): a
  // candidate partner's depth along the epipolar line must lie within the range of inverse depths of
  // the depth_range_neighbours verified matches (refinement inliers) nearest to the junction in
  // image 1, widened by the cheirality tolerance at refine_gate_sigmas. 0: off.
  int depth_range_neighbours = 12;
  // Before that, drop the verified matches that fail the same test against the other verified ones
  // (a wrong verified match at a near depth would widen its neighbours' range).
  bool depth_range_screen_verified = true;
  // Partial junction correspondence in the guided pass only (not in the paper; docs/matching.md,
  // "Partial correspondence"): a junction of k >= 2 segments left unmatched may match one of k + 1
  // (a segment missed in one frame) through its best common subset, rho2 counting the missing
  // segment's term as 0, by rule (38) among the junctions the full pass left unmatched, under the
  // same local depth range test as the full pass. Tracks (PartnerSegment) and the match overlay take
  // partial matches; BuildTracks does not join a partial match with a T or an X on either side (an
  // occlusion seen with one arm hidden: most partial L-T matches are off any true vertex). On by
  // default: it meets the matching goals (generated recall 80.6 -> 91.3 % with the odometry at
  // 99.4 % precision, VGG consecutive precision 98.5 -> 97.7 %), and with the T/X rule in the
  // tracks the reconstruction is about as good as without partial matches (docs/matching_results.md,
  // "Partial correspondence under the local depth range", and docs/backend_results.md).
  bool match_partial = true;
  // The two rules on the segment a partial pair leaves out (docs/matching.md, "Partial
  // correspondence"; JunctionSimilarity::PartialRho). (a) It is not half of a straight line through
  // the location (against occlusion T's read as L's). Off by default: the depth range test now
  // rejects most of those (without rule (a), VGG 96.0 -> 97.7 %), and turning the rule on costs far
  // more recall than it buys precision: VGG 97.7 -> 98.3 % precision for 91.3 -> 80.3 % recall,
  // generated 99.4 % either way for 91.3 -> 87.7 %, held out 99.0 -> 99.2 % for 89.3 -> 81.1 %.
  bool partial_rule_not_line_half = false;
  // (b) The kept segments have as many straight lines through the location as the smaller junction
  // (a T without its stem is a line, not an L). Kept: without it VGG precision 97.7 -> 97.4 % for
  // +0.2 point of generated recall.
  bool partial_rule_same_lines = true;
  // One-common-segment matches in the partial pass (not in the paper; docs/matching.md, "One
  // common segment"): two L's left unmatched that share one segment (two corners of one 3-edge
  // vertex, edges 1-2 in one frame and 2-3 in the other; JunctionSimilarity::OneCommonRho) are a
  // candidate only with topology support: a topology edge from the shared segment to a junction the
  // guided pass matched, and in the other image the partner's shared segment's edge to that
  // junction's partner, through the segment that match pairs. On by default since session 8, with
  // the junction options that add corners beyond taken end-points (JunctionDetectorOptions): with
  // those on, the generated corridor's recall is 89.9 % without it and 91.1 % with it, precision
  // 99.7 % (docs/matching_results.md, "Session 7, part 2" and "Session 8"; docs/junction_results.md,
  // "Session 8, the lead's decision", for the end-to-end cost).
  bool match_one_common = true;
  // Rule (38)'s margin between rivals on one arm (not in the paper; docs/matching.md, "Rivals on
  // one arm"): two candidates for one junction whose other junctions hold one detected line segment
  // pointing the same way and pair it with the same segment of the shared partner (a corner beyond
  // a taken end-point and the junction holding that end) do not count against each other; the
  // larger must still beat every other rival by tau2. On by default: with the default junctions
  // the generated corridor's recall 90.0 -> 90.4 % at the same precision, VGG consecutive 98.2 %
  // either way, every held-out wireframe still >= 0.90 (docs/matching_results.md, "Session 8").
  bool match_rivals_on_one_arm = true;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("MatchingOptions: " + what); };
    if (!(max_epipolar_distance_px > 0 && std::isfinite(max_epipolar_distance_px))) {
      return bad("max_epipolar_distance_px must be finite and > 0");
    }
    if (!(tau1 >= 0 && std::isfinite(tau1))) return bad("tau1 must be finite and >= 0");
    if (!(tau2 >= 0 && std::isfinite(tau2))) return bad("tau2 must be finite and >= 0");
    if (!endpoint_model.Check()) return bad("endpoint_model needs finite lambda > 0 and mu > 0");
    if (!(parallel_tolerance_px > 0 && std::isfinite(parallel_tolerance_px))) {
      return bad("parallel_tolerance_px must be finite and > 0");
    }
    if (!(cyclic_order_min_angle_deg >= 0 && cyclic_order_min_angle_deg < 45)) {
      return bad("cyclic_order_min_angle_deg must be in [0, 45)");
    }
    if (!(band_sigmas > 0 && std::isfinite(band_sigmas))) return bad("band_sigmas must be finite and > 0");
    if (!(location_sigma_px >= 0 && std::isfinite(location_sigma_px))) {
      return bad("location_sigma_px must be finite and >= 0");
    }
    if (!(refine_gate_sigmas > 0 && std::isfinite(refine_gate_sigmas))) {
      return bad("refine_gate_sigmas must be finite and > 0");
    }
    if (refine_min_inliers < 0) return bad("refine_min_inliers must be >= 0");
    if (depth_range_neighbours < 0) return bad("depth_range_neighbours must be >= 0");
    if (refine_geometry && !(location_sigma_px > 0)) {
      return bad("refine_geometry needs location_sigma_px > 0");
    }
    return Status::Ok();
  }
};

}  // namespace sfm
