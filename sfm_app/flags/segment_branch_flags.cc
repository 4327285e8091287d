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
DEFINE_bool(short_pieces_at_contacts, kDefaults.short_pieces_at_contacts,
            "Fast segments: keep a piece shorter than min_length that meets a long segment (an L or a T) "
            "if its NFA against the family of such pieces passes.");
DEFINE_double(min_contact_length, kDefaults.min_contact_length,
              "Fast segments (with short_pieces_at_contacts): shortest piece kept, px.");

namespace sfm {

void SegmentBranchesFromFlags(FastSegmentOptions* options) {
  options->branches_at_free_ends = FLAGS_branches_at_free_ends;
  options->branches_to_far_corners = FLAGS_branches_to_far_corners;
  options->bridges_past_corners = FLAGS_bridges_past_corners;
  options->short_pieces_at_contacts = FLAGS_short_pieces_at_contacts;
  options->min_contact_length = FLAGS_min_contact_length;
}

}  // namespace sfm
