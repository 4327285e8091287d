#include "frontend/segments/endpoint_fit.h"

#include <cmath>

#include <glog/logging.h>

namespace sfm {

double EndpointLogLikelihood(const EndpointModel& model, const std::vector<double>& t_samples) {
  const double log_norm = std::log(model.lambda * model.mu / (model.lambda + model.mu));
  double sum = 0;
  for (const double t : t_samples) sum += log_norm + std::log(model.F(t));
  return sum;
}

EndpointModel FitEndpointModel(const std::vector<double>& t_samples) {
  double beyond = 0, short_of = 0;
  for (const double t : t_samples) (t >= 0 ? beyond : short_of) += std::abs(t);
  CHECK(beyond > 0 && short_of > 0) << "FitEndpointModel needs samples on both sides of 0";
  const double n = static_cast<double>(t_samples.size());
  const double a = beyond / n, b = short_of / n, root = std::sqrt(a * b);
  EndpointModel model;
  model.lambda = 1 / (a + root);
  model.mu = 1 / (b + root);
  return model;
}

}  // namespace sfm
