#include "frontend/segments/endpoint_fit.h"

#include <random>

#include <gtest/gtest.h>

namespace sfm {
namespace {

// Samples of the normalised eq. (5): t >= 0 with probability mu/(lambda+mu), then exponential.
std::vector<double> Draw(const EndpointModel& model, int n, unsigned seed) {
  std::mt19937 random(seed);
  std::bernoulli_distribution beyond(model.mu / (model.lambda + model.mu));
  std::exponential_distribution<double> extension(model.lambda), shortening(model.mu);
  std::vector<double> t(n);
  for (double& v : t) v = beyond(random) ? extension(random) : -shortening(random);
  return t;
}

TEST(EndpointFitTest, RecoversKnownParametersFromSamples) {
  for (const EndpointModel truth : {EndpointModel{0.5, 2.0}, EndpointModel{1.0, 0.2}, EndpointModel{0.3, 0.3}}) {
    const EndpointModel fitted = FitEndpointModel(Draw(truth, 20000, 11));
    // Relative standard error of an exponential rate from ~10000 samples is ~1%: allow 5%.
    EXPECT_NEAR(fitted.lambda / truth.lambda, 1.0, 0.05) << truth.lambda << " " << truth.mu;
    EXPECT_NEAR(fitted.mu / truth.mu, 1.0, 0.05) << truth.lambda << " " << truth.mu;
  }
}

TEST(EndpointFitTest, ClosedFormIsTheLikelihoodMaximum) {
  const std::vector<double> t = Draw(EndpointModel{0.7, 1.6}, 500, 5);
  const EndpointModel best = FitEndpointModel(t);
  const double best_ll = EndpointLogLikelihood(best, t);
  for (const double dl : {-0.02, 0.0, 0.02}) {
    for (const double dm : {-0.02, 0.0, 0.02}) {
      if (dl == 0 && dm == 0) continue;
      EXPECT_LT(EndpointLogLikelihood(EndpointModel{best.lambda + dl, best.mu + dm}, t), best_ll);
    }
  }
}

TEST(EndpointFitDeathTest, NeedsSamplesOnBothSides) {
  EXPECT_DEATH(FitEndpointModel({0.5, 1.0, 2.0}), "both sides");
}

}  // namespace
}  // namespace sfm
