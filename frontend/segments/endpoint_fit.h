// Maximum-likelihood estimate of the end-point model of eq. (5) from observed end-point offsets.
#pragma once

#include <vector>

#include "frontend/segments/endpoint_model.h"

namespace sfm {

// Log-likelihood of samples t (pixels; eq. 8 sign: detected minus true, outward positive) under the
// normalised two-sided exponential p(t) = lambda*mu/(lambda+mu) * f(t), f of eq. (5).
double EndpointLogLikelihood(const EndpointModel& model, const std::vector<double>& t_samples);

// The (lambda, mu) maximising EndpointLogLikelihood. With a = (sum of t >= 0) / N and
// b = (sum of -t over t < 0) / N, setting both derivatives to zero gives the closed form
//   lambda = 1 / (a + sqrt(a b)),   mu = 1 / (b + sqrt(a b)).
// Needs at least one positive and one negative sample (otherwise one parameter is unbounded).
EndpointModel FitEndpointModel(const std::vector<double>& t_samples);

}  // namespace sfm
