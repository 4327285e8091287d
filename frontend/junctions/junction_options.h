// Settings of junction detection (paper section 2.2). docs/junctions.md says how each default was
// chosen.
#pragma once

#include <cmath>
#include <string>

#include "frontend/segments/endpoint_model.h"
#include "util/status.h"

namespace sfm {

struct JunctionDetectorOptions {
  // f(t) of eq. (5), t = detected minus true end-point along the outward direction (eq. 8), pixels.
  EndpointModel endpoint_model;
  // A pair of segments meets at a junction when its junction probability (the product of f over
  // the end-points moved, so 1 for no change) reaches this. Unitless, in (0, 1].
  // Rule: if t follows the model (density proportional to f), -ln f(t) is exponential of rate 1 on
  // either branch, whatever lambda and mu, so -ln of a true pair's probability is Gamma(2, 1). The
  // threshold keeps 90 % of true pairs: exp(-x) with e^-x (1 + x) = 0.1, x = 3.8897.
  double min_probability = 0.0205;
  // Hard limit on how far any end-point may be moved to reach the junction, pixels; it also bounds
  // the neighbourhood searched. With the default model the probability test binds first.
  double max_gap_px = 12.0;
  // Lines closer to parallel than this are never intersected (eq. 6 is ill-conditioned there):
  // they may only continue one another. A 3-junction with two junction segments within this of
  // opposite is a T. Degrees.
  double collinear_tolerance_deg = 5.0;
  // Two near-parallel pieces continue one another only when each near end-point lies within this
  // of the other piece's line, pixels.
  double collinear_max_offset_px = 1.5;
  // A junction lies inside a segment (the bar of a T, a crossing of an X) when it is at least this
  // far from both of the segment's end-points; closer, the end-point is moved instead. Pixels.
  double min_arm_px = 3.0;
  // Acute corners (an L contact, both end-points moved): near a corner of angle theta the other
  // edge comes within an edge filter's scale s of a segment's line at s / sin(theta) from the
  // vertex, and there the two edges' responses merge, so the segment stops about s / sin(theta)
  // short instead of about s at a right angle (the shortfall eq. (5)'s fitted f already holds). The
  // shortfall t < 0 of each end-point is reduced by s (1 / sin(theta) - 1), never past 0, before
  // f(t) is evaluated. This is s, px; 0 leaves eq. (5) as it is. Off by default: with s = 1 px (the
  // detector's filter scale) junction recall on generated vertices rises 85.3 -> 85.7 % at
  // precision 92.2 -> 92.5 %, but VGG matching precision falls 0.2-0.7 points on odometry seeds 1-3
  // (docs/junction_results.md, "Session 5").
  double acute_shortfall_px = 0.0;
  // How the best conflict-free set of candidate junctions is chosen (docs/junctions.md, step 3).
  // false: the largest total of the paper's score (the sum of pairwise probabilities). true: the
  // largest total log-likelihood ratio of the end-points explained, each end-point counted once,
  // ln f(t) - ln sqrt(min_probability) when positive (junction_detector.cc, EndLikelihoodWeight).
  // The output score stays the paper's. On by default (since the end of session 5): junction recall
  // on generated vertices 85.3 -> 86.4 % (held-out 82.6 -> 84.6 %), precision 92.2 -> 93.4 %, median
  // error 0.257 -> 0.248 px. It had cost VGG matching precision on some odometry seeds (96.7 % on
  // seed 3) through the matcher's pair refinement falling back to the odometry's band, which the
  // refinement's constrained search (MatchingOptions::refine_constrain_to_prior_gate) now avoids:
  // every one of 16 seeds >= 98.1 % (docs/junction_results.md, docs/matching_results.md "Session 5").
  bool choose_by_end_likelihood = true;
  // Two true vertices a few pixels apart on one line (a stub of a segment A's line between them):
  // A's end-point belongs to the junction W at the first, so the second gets none. With these,
  // A's line also serves a corner with a segment B at least min_arm_px beyond W, when that corner
  // explains B's end-point better (junction_detector.cc, CornersBeyondTakenEnds; docs/junctions.md
  // step 3): corner_beyond_taken_end replaces B's T by the corner (the number of junctions is
  // unchanged), corner_beyond_taken_end_free adds the corner when B's end-point is in no junction.
  // Need choose_by_end_likelihood. On by default since session 8: detectable generated vertices
  // with a junction within 3 px 88.5 -> 90.8 % (one-to-one 86.9 -> 89.4 %) at precision 93.6 ->
  // 93.8 %; off in session 7 because the corridor's matching recall fell under 90 %, which the
  // matcher's rivals-on-one-arm rule and one-common matches restore (MatchingOptions). Measured in
  // docs/junction_results.md, "Session 7" and "Session 8, the lead's decision".
  bool corner_beyond_taken_end = true;
  bool corner_beyond_taken_end_free = true;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("JunctionDetectorOptions: " + what); };
    if (!endpoint_model.Check()) return bad("endpoint_model needs finite lambda > 0 and mu > 0");
    if (!(min_probability > 0 && min_probability <= 1)) return bad("min_probability must be in (0, 1]");
    if (!(max_gap_px > 0 && std::isfinite(max_gap_px))) return bad("max_gap_px must be finite and > 0");
    if (!(collinear_tolerance_deg > 0 && collinear_tolerance_deg < 45)) {
      return bad("collinear_tolerance_deg must be in (0, 45)");
    }
    if (!(collinear_max_offset_px >= 0 && std::isfinite(collinear_max_offset_px))) {
      return bad("collinear_max_offset_px must be finite and >= 0");
    }
    if (!(min_arm_px >= 0 && std::isfinite(min_arm_px))) return bad("min_arm_px must be finite and >= 0");
    if (!(acute_shortfall_px >= 0 && std::isfinite(acute_shortfall_px))) {
      return bad("acute_shortfall_px must be finite and >= 0");
    }
    return Status::Ok();
  }
};

}  // namespace sfm
