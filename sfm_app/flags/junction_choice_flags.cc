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

namespace sfm {

void JunctionChoiceFromFlags(JunctionDetectorOptions* options) {
  options->choose_by_end_likelihood = FLAGS_choose_by_end_likelihood;
  options->acute_shortfall_px = FLAGS_acute_shortfall_px;
}

}  // namespace sfm
