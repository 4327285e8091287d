// Settings of junction matching (paper section 4). docs/matching.md says how each default was chosen.
#pragma once

#include <cmath>
#include <string>

#include "frontend/segments/endpoint_model.h"
#include "util/status.h"

namespace sfm {

// The two forms of rho1 in section 4.1.
enum class Rho1Kind {
  kExponential,  // eq. (31): 0.5*(exp(-w d) + exp(-w d')), exp(-w R) = 0.01
  kLinear,       // footnote 10: 0.5*(2 - (d + d')/R), more tolerant of a poor epipolar geometry
};

// "exponential" or "linear".
inline const char* ToString(Rho1Kind kind) { return kind == Rho1Kind::kLinear ? "linear" : "exponential"; }
// The kind named `name` (as ToString writes it), or an error naming the choices.
inline Status FromString(const std::string& name, Rho1Kind* kind) {
  for (const Rho1Kind k : {Rho1Kind::kExponential, Rho1Kind::kLinear}) {
    if (name == ToString(k)) {
      *kind = k;
      return Status::Ok();
    }
  }
  return Status::Error("'" + name + "' is not a rho1 kind ('exponential' or 'linear')");
}

struct MatchingOptions {
  // R of section 4.1: largest distance of a junction location from the epipolar line of its
  // partner's location, pixels; a pair farther either way is unmatched. Used where no pair pose is
  // given (or use_pose_band is false); the paper's corridor value (docs/matching.md, "Defaults").
  double max_epipolar_distance_px = 10.0;
  // tau1 of (38): a candidate pair needs a similarity above this. Unitless, >= 0; the paper's 0.
  double tau1 = 0.0;
  // tau2 of (38): the chosen partner must beat every other candidate, both ways, by more than this.
  // Unitless, >= 0; the paper's 0.1.
  double tau2 = 0.1;
  // rho1 of section 4.1; linear (footnote 10) for an odometry-made epipolar geometry.
  Rho1Kind rho1_kind = Rho1Kind::kLinear;
  // true: rule (38) on sigma (section 4.2, junction topology); false: on plain rho (34).
  bool use_topology = true;
  // f(t) of eq. (5), 1/pixels: the model junction detection uses (the pipeline hands it down,
  // PipelineOptions::Matching).
  EndpointModel endpoint_model;
  // The epipolar line of an end-point counts as parallel to the partner segment (section 3.2, last
  // paragraph) when, along the partner's length, it departs from the partner's line by at most
  // this: nearer parallel, the intersection p'e is set by noise. Pixels, > 0.
  double parallel_tolerance_px = 1.0;
  // (36) is not tested on two consecutive segments closer than this to collinear (a T's bar has no
  // reliable turn): JunctionDetectorOptions::collinear_tolerance_deg. Degrees, in [0, 45).
  double cyclic_order_min_angle_deg = 5.0;

  // With a pair pose and its covariance (PairGeometry; docs/matching.md, "Pose uncertainty and
  // cheirality"), not in the paper:
  // true: each pair's search band, band_sigmas * sqrt(sigma_pose^2 + 2 location_sigma_px^2) in each
  // image, replaces R; false: R, as the paper.
  bool use_pose_band = true;
  double band_sigmas = 3.0;  // unitless, > 0: a two-sided 99.7 % Gaussian gate
  // Standard deviation of a junction location the band, cheirality and refinement gates assume,
  // pixels, >= 0: half a pixel, the detector's error on rendered images (kJunctionLocationErrorPx,
  // 0.3 px) with room for real images (docs/matching.md, "Pose uncertainty and cheirality").
  double location_sigma_px = 0.5;
  // Reject pairs whose triangulation lies behind camera 1 or 2 by more than band_sigmas of the
  // parallax's uncertainty (PassesCheirality).
  bool use_cheirality = true;

  // Geometric verification and the guided second pass (docs/matching.md, "Geometric verification
  // and the guided pass"): the pair's pose re-estimated from the first pass's matches with the
  // odometry as prior (RefinePairGeometry), then rule (38) again in its band of refine_gate_sigmas,
  // then the partial, one-common-segment matches of the leftovers.
  bool refine_geometry = true;
  // Unitless, > 0: the two-sided 99 % Gaussian point, the level of the prior's consistency test.
  double refine_gate_sigmas = 2.576;
  // Fewest matches within the gate for a refined pose: three per degree of freedom of (5).
  int refine_min_inliers = 15;
  // Verified matches nearest to a junction whose inverse-depth range its partner's depth must lie
  // in (docs/matching.md, "The local depth range"; 0: no test). 12: the fewest for which a point
  // lies in its neighbours' hull with probability >= 99 %.
  int depth_range_neighbours = 12;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("MatchingOptions: " + what); };
    if (!(max_epipolar_distance_px > 0 && std::isfinite(max_epipolar_distance_px))) {
      return bad("max_epipolar_distance_px must be finite and > 0");
    }
    if (!(tau1 >= 0 && std::isfinite(tau1))) return bad("tau1 must be finite and >= 0");
    if (!(tau2 >= 0 && std::isfinite(tau2))) return bad("tau2 must be finite and >= 0");
    if (!endpoint_model.Check()) return bad("endpoint_model needs finite lambda > 0 and mu > 0");
    if (!(parallel_tolerance_px > 0 && std::isfinite(parallel_tolerance_px))) {
      return bad("parallel_tolerance_px must be finite and > 0");
    }
    if (!(cyclic_order_min_angle_deg >= 0 && cyclic_order_min_angle_deg < 45)) {
      return bad("cyclic_order_min_angle_deg must be in [0, 45)");
    }
    if (!(band_sigmas > 0 && std::isfinite(band_sigmas))) return bad("band_sigmas must be finite and > 0");
    if (!(location_sigma_px >= 0 && std::isfinite(location_sigma_px))) {
      return bad("location_sigma_px must be finite and >= 0");
    }
    if (!(refine_gate_sigmas > 0 && std::isfinite(refine_gate_sigmas))) {
      return bad("refine_gate_sigmas must be finite and > 0");
    }
    if (refine_min_inliers < 0) return bad("refine_min_inliers must be >= 0");
    if (depth_range_neighbours < 0) return bad("depth_range_neighbours must be >= 0");
    if (refine_geometry && !(location_sigma_px > 0)) {
      return bad("refine_geometry needs location_sigma_px > 0");
    }
    return Status::Ok();
  }
};

}  // namespace sfm
