#include "sfm_app/flags/detector_flags.h"

namespace {
const sfm::JunctionDetectorOptions kDefaults;
}  // namespace

DEFINE_double(
    lambda, kDefaults.endpoint_model.lambda,
    "End-point model eq. (5): decay for a detected end-point beyond the junction (t >= 0, too long), "
    "1/px.");
DEFINE_double(
    mu, kDefaults.endpoint_model.mu,
    "End-point model eq. (5): decay for a detected end-point short of the junction (t < 0, too short), "
    "1/px.");
DEFINE_double(min_probability, kDefaults.min_probability, "Pairwise junction probability threshold, (0, 1].");
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
  options->endpoint_model.lambda = FLAGS_lambda;
  options->endpoint_model.mu = FLAGS_mu;
  options->min_probability = FLAGS_min_probability;
  options->max_gap_px = FLAGS_max_gap_px;
  options->collinear_tolerance_deg = FLAGS_collinear_tolerance_deg;
  options->collinear_max_offset_px = FLAGS_collinear_max_offset_px;
  options->min_arm_px = FLAGS_min_arm_px;
}

}  // namespace sfm
