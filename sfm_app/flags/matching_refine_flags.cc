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

namespace sfm {

void MatchingRefineFromFlags(MatchingOptions* matching) {
  matching->refine_geometry = FLAGS_match_refine;
  matching->refine_gate_sigmas = FLAGS_match_refine_gate;
  matching->refine_min_inliers = FLAGS_match_refine_min_inliers;
}

}  // namespace sfm
