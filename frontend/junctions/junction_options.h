// Settings of junction detection (paper section 2.2). docs/junctions.md says how each default was
// chosen.
#pragma once

#include <cmath>
#include <string>

#include "frontend/segments/endpoint_model.h"
#include "util/status.h"

namespace sfm {

struct JunctionDetectorOptions {
  // f(t) of eq. (5), t = detected minus true end-point along the outward direction (eq. 8), pixels.
  EndpointModel endpoint_model;
  // A pair of segments meets at a junction when its junction probability (the product of f over
  // the end-points moved, so 1 for no change) reaches this. Unitless, in (0, 1]. It keeps 90 % of
  // true pairs whatever lambda and mu (-ln of a true pair's probability is Gamma(2, 1);
  // docs/junctions.md, "Defaults").
  double min_probability = 0.0205;
  // Hard limit on how far any end-point may be moved to reach the junction, pixels; it also bounds
  // the neighbourhood searched. With the default model the probability test binds first.
  double max_gap_px = 12.0;
  // Lines closer to parallel than this are never intersected (eq. 6 is ill-conditioned there):
  // they may only continue one another. A 3-junction with two junction segments within this of
  // opposite is a T. Degrees.
  double collinear_tolerance_deg = 5.0;
  // Two near-parallel pieces continue one another only when each near end-point lies within this
  // of the other piece's line, pixels.
  double collinear_max_offset_px = 1.5;
  // A junction lies inside a segment (the bar of a T, a crossing of an X) when it is at least this
  // far from both of the segment's end-points; closer, the end-point is moved instead. Pixels.
  double min_arm_px = 3.0;

  Status Check() const {
    auto bad = [](const std::string& what) { return Status::Error("JunctionDetectorOptions: " + what); };
    if (!endpoint_model.Check()) return bad("endpoint_model needs finite lambda > 0 and mu > 0");
    if (!(min_probability > 0 && min_probability <= 1)) return bad("min_probability must be in (0, 1]");
    if (!(max_gap_px > 0 && std::isfinite(max_gap_px))) return bad("max_gap_px must be finite and > 0");
    if (!(collinear_tolerance_deg > 0 && collinear_tolerance_deg < 45)) {
      return bad("collinear_tolerance_deg must be in (0, 45)");
    }
    if (!(collinear_max_offset_px >= 0 && std::isfinite(collinear_max_offset_px))) {
      return bad("collinear_max_offset_px must be finite and >= 0");
    }
    if (!(min_arm_px >= 0 && std::isfinite(min_arm_px))) return bad("min_arm_px must be finite and >= 0");
    return Status::Ok();
  }
};

}  // namespace sfm
