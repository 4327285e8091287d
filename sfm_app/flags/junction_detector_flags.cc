#include "sfm_app/flags/detector_flags.h"

namespace {
const sfm::JunctionDetectorOptions kDefaults;
}  // namespace

// The same names as junction_sfm's and the matching apps' (matching_flags.cc); no app links both groups.
DEFINE_double(endpoint_lambda, kDefaults.endpoint_model.lambda,
              "End-point model eq. (5): decay, 1/px, of a detected end-point lying beyond the true one "
              "(t >= 0).");
DEFINE_double(endpoint_mu, kDefaults.endpoint_model.mu,
              "End-point model eq. (5): decay, 1/px, of a detected end-point falling short of the true one "
              "(t < 0).");
DEFINE_double(junction_min_probability, kDefaults.min_probability,
              "Junction threshold: least junction probability of a pair of segments, (0, 1].");
DEFINE_double(max_gap_px, kDefaults.max_gap_px, "Largest move of an end-point to reach a junction, px.");
DEFINE_double(collinear_tolerance_deg, kDefaults.collinear_tolerance_deg,
              "Near-parallel limit: lines closer to parallel are never intersected; T tolerance, degrees.");
DEFINE_double(collinear_max_offset_px, kDefaults.collinear_max_offset_px,
              "Offset allowed between two pieces of one broken line, px.");
DEFINE_double(
    min_arm_px, kDefaults.min_arm_px,
    "Smallest arm of a T bar or X: a junction inside a segment must be this far from its ends (else "
    "the end moves), px.");

namespace sfm {

void JunctionDetectorFromFlags(JunctionDetectorOptions* options) {
  options->endpoint_model.lambda = FLAGS_endpoint_lambda;
  options->endpoint_model.mu = FLAGS_endpoint_mu;
  options->min_probability = FLAGS_junction_min_probability;
  options->max_gap_px = FLAGS_max_gap_px;
  options->collinear_tolerance_deg = FLAGS_collinear_tolerance_deg;
  options->collinear_max_offset_px = FLAGS_collinear_max_offset_px;
  options->min_arm_px = FLAGS_min_arm_px;
}

}  // namespace sfm
