#include "sfm_app/flags/detector_flags.h"

namespace {
const sfm::FastSegmentOptions kDefaults;
}  // namespace

DEFINE_bool(branches_at_free_ends, kDefaults.branches_at_free_ends,
            "Fast segments: look for a corner's missing side along rays from free segment end-points.");
DEFINE_bool(branches_to_far_corners, kDefaults.branches_to_far_corners,
            "Fast segments (with branches_at_free_ends): a branch ending at another corner is measured "
            "from corner to corner.");
DEFINE_bool(bridges_past_corners, kDefaults.bridges_past_corners,
            "Fast segments (with branches_at_free_ends): continue a segment's line across the gap to a "
            "free end when the gradient there is aligned with it.");

namespace sfm {

void SegmentBranchesFromFlags(FastSegmentOptions* options) {
  options->branches_at_free_ends = FLAGS_branches_at_free_ends;
  options->branches_to_far_corners = FLAGS_branches_to_far_corners;
  options->bridges_past_corners = FLAGS_bridges_past_corners;
}

}  // namespace sfm
