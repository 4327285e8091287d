#include "sfm_app/flags/detector_flags.h"

namespace {
const sfm::MatchingOptions kDefaults;
}  // namespace

DEFINE_bool(
    match_refine, kDefaults.refine_geometry,
    "Verify each pair's matches: refine the pair's pose from its first-pass matches (odometry as prior), "
    "then match again in the refined geometry's band (geometric verification and guided pass, "
    "docs/matching.md; with the pose: not with --match_pose=false where an app has it).");
DEFINE_double(match_refine_gate, kDefaults.refine_gate_sigmas,
              "With --match_refine: band of the guided second pass, in standard deviations of the refined "
              "epipolar distance.");
DEFINE_int32(
    match_refine_min_inliers, kDefaults.refine_min_inliers,
    "With --match_refine: fewest supporting first-pass matches for the refined pose; fewer: keep the "
    "first pass.");
DEFINE_bool(
    match_refine_constrain, kDefaults.refine_constrain_to_prior_gate,
    "With --match_refine: when the refined pose lies beyond the odometry's 99 % ellipsoid, take the best "
    "pose inside it before keeping the first pass (docs/matching.md, \"Refinement fall-backs\").");
DEFINE_bool(match_partial, kDefaults.match_partial,
            "With --match_refine: in the guided pass, match junctions of k and k + 1 segments left unmatched "
            "through their best common subset (partial correspondence, docs/matching.md).");
DEFINE_bool(
    match_partial_rule_a, kDefaults.partial_rule_not_line_half,
    "With --match_partial: rule (a), the left-out segment may not be half of a line through the junction.");
DEFINE_bool(match_one_common, kDefaults.match_one_common,
            "With --match_partial: also match two leftover L's sharing one segment (two corners of one "
            "vertex) when a matched neighbour through that segment supports it (docs/matching.md).");
DEFINE_bool(match_rivals_on_one_arm, kDefaults.match_rivals_on_one_arm,
            "Rule (38)'s margin ignores a rival that holds the same detected segment, pointing the same "
            "way, paired with the same segment of the shared partner (docs/matching.md).");

namespace sfm {

void MatchingRefineFromFlags(MatchingOptions* matching) {
  matching->refine_geometry = FLAGS_match_refine;
  matching->refine_gate_sigmas = FLAGS_match_refine_gate;
  matching->refine_min_inliers = FLAGS_match_refine_min_inliers;
  matching->refine_constrain_to_prior_gate = FLAGS_match_refine_constrain;
  matching->match_partial = FLAGS_match_partial;
  matching->partial_rule_not_line_half = FLAGS_match_partial_rule_a;
  matching->match_one_common = FLAGS_match_one_common;
  matching->match_rivals_on_one_arm = FLAGS_match_rivals_on_one_arm;
}

}  // namespace sfm
