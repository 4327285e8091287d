#include "sfm_app/flags/detector_flags.h"

namespace {
const sfm::JunctionDetectorOptions kDefaults;
}  // namespace

DEFINE_bool(choose_by_end_likelihood, kDefaults.choose_by_end_likelihood,
            "Junctions: choose between conflicting junctions by the log-likelihood of the end-points they "
            "explain (not the sum of pair probabilities).");
DEFINE_double(acute_shortfall_px, kDefaults.acute_shortfall_px,
              "Junctions: an L contact's end-point shortfall is reduced by this times (1 / sin(angle) - 1) "
              "before eq. (5), px (0: off).");

DEFINE_bool(corner_beyond_taken_end, kDefaults.corner_beyond_taken_end,
            "Junctions: a T whose stem ends at another segment's line a few px beyond that segment's "
            "end-point (held by another junction) becomes the corner of the two (default off).");
DEFINE_bool(corner_beyond_taken_end_free, kDefaults.corner_beyond_taken_end_free,
            "Junctions: a segment end-point in no junction at another segment's line a few px beyond that "
            "segment's end-point (held by another junction) gets the corner of the two (default off).");

namespace sfm {

void JunctionChoiceFromFlags(JunctionDetectorOptions* options) {
  options->choose_by_end_likelihood = FLAGS_choose_by_end_likelihood;
  options->acute_shortfall_px = FLAGS_acute_shortfall_px;
  options->corner_beyond_taken_end = FLAGS_corner_beyond_taken_end;
  options->corner_beyond_taken_end_free = FLAGS_corner_beyond_taken_end_free;
}

}  // namespace sfm
