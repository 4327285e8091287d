#include "sfm_app/flags/detector_flags.h"

namespace {
const sfm::JunctionDetectorOptions kJunctionDefaults;
const sfm::MatchingOptions kDefaults;
}  // namespace

// "With the pose": the pair's pose and its uncertainty, which junction_sfm always gives the matcher
// and the apps with a --match_pose flag unless it is false.
DEFINE_double(endpoint_lambda, kJunctionDefaults.endpoint_model.lambda,
              "End-point model eq. (5): decay, 1/px, of a detected end-point lying beyond the true one "
              "(t >= 0; junction detection and matching).");
DEFINE_double(endpoint_mu, kJunctionDefaults.endpoint_model.mu,
              "End-point model eq. (5): decay, 1/px, of a detected end-point falling short of the true one "
              "(t < 0; junction detection and matching).");
DEFINE_double(junction_min_probability, kJunctionDefaults.min_probability,
              "Junction threshold: least junction probability of a pair of segments, (0, 1].");
DEFINE_double(
    match_max_distance, kDefaults.max_epipolar_distance_px,
    "R: largest distance, px, of a junction from its partner's epipolar line (used without the pose "
    "band: --match_pose_band=false, or --match_pose=false where an app has it).");
DEFINE_double(match_tau1, kDefaults.tau1, "tau1 of rule (38): least similarity of a match.");
DEFINE_double(match_tau2, kDefaults.tau2,
              "tau2 of rule (38): how much the best candidate must beat the second, both ways.");
DEFINE_string(match_rho1, sfm::ToString(kDefaults.rho1_kind),
              "rho1 of eq. (31): 'exponential' or 'linear' (footnote 10; more tolerant of a poor epipolar "
              "geometry).");
DEFINE_bool(match_pose_band, kDefaults.use_pose_band,
            "Set each pair's search band from the pose's uncertainty (the odometry noise model of "
            "sequence.yaml) instead of R (with the pose: not with --match_pose=false where an app has it).");
DEFINE_double(match_band_sigmas, kDefaults.band_sigmas,
              "Width of the search band in standard deviations of the epipolar distance.");
DEFINE_bool(match_cheirality, kDefaults.use_cheirality,
            "Reject pairs that would triangulate behind either camera (with the pose: not with "
            "--match_pose=false where an app has it).");
DEFINE_bool(match_topology, kDefaults.use_topology,
            "Match on sigma (junction topology, section 4.2) rather than on plain rho (34).");

namespace sfm {

bool MatchingFromFlags(JunctionDetectorOptions* junctions, MatchingOptions* matching, std::string* error) {
  const EndpointModel endpoint_model{FLAGS_endpoint_lambda, FLAGS_endpoint_mu};
  junctions->endpoint_model = endpoint_model;
  junctions->min_probability = FLAGS_junction_min_probability;
  matching->endpoint_model = endpoint_model;
  matching->max_epipolar_distance_px = FLAGS_match_max_distance;
  matching->tau1 = FLAGS_match_tau1;
  matching->tau2 = FLAGS_match_tau2;
  matching->use_pose_band = FLAGS_match_pose_band;
  matching->band_sigmas = FLAGS_match_band_sigmas;
  matching->use_cheirality = FLAGS_match_cheirality;
  matching->use_topology = FLAGS_match_topology;
  const Status status = FromString(FLAGS_match_rho1, &matching->rho1_kind);
  if (!status.ok()) *error = "--match_rho1: " + status.message();
  return status.ok();
}

}  // namespace sfm
