// The end-point uncertainty model of paper eq. (5).
//
// t is the signed distance from the true to the detected end-point along the segment's outward
// direction (eq. 8: detected minus true; t > 0: the detected segment is too long, t < 0: too short).
//   f(t) = exp(-lambda * t)  for t >= 0
//   f(t) = exp( mu * t)      for t <  0
// The normalising factor lambda*mu/(lambda+mu) is dropped, as in the paper, so f(0) = 1.
// The defaults are the maximum-likelihood fit (FitEndpointModel) to the vertex ends of the generated
// sequences of benchmark_junctions with the fast segments at commit 2db1a25; see
// docs/endpoint_model.md.
#pragma once

#include <cmath>

namespace sfm {

struct EndpointModel {
  double lambda = 0.844;  // 1/pixels: decay for detected end-points beyond the true one (t >= 0)
  double mu = 0.353;      // 1/pixels: decay for detected end-points short of the true one (t < 0)

  double F(double t) const { return t >= 0 ? std::exp(-lambda * t) : std::exp(mu * t); }
  bool Check() const { return lambda > 0 && mu > 0 && std::isfinite(lambda) && std::isfinite(mu); }
};

}  // namespace sfm
