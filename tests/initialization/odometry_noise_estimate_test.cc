// The odometry's noise measured against the images recovers the generator's noise model.
#include "backend/initialization/odometry_noise_estimate.h"

#include <gtest/gtest.h>

#include "sequences/generator/odometry_noise.h"
#include "tests/initialization/synthetic_drive.h"

namespace sfm {
namespace {

// 120 steps, heading noise and bias 6x the generator's default; the images' rotations carry 1e-4
// rad of noise. The figure: within 25 % of the model. Observed errors over these seeds:
// sigma within about 15 %, bias within 0.001 rad (a sixth of it).
TEST(OdometryNoiseEstimate, RecoversTheGeneratorsRotationNoiseAndBias) {
  const Pose3 base_T_camera = TestBaseTCamera();
  const std::vector<Pose3> truth = TrueDrive(121, 0.03);
  OdometryNoiseOptions noise;
  noise.heading_sigma = 0.012;
  noise.heading_bias = 0.006;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    const OdometryRotationEstimate estimate = EstimateOdometryRotationNoise(
        SimulateOdometry(truth, noise, seed), base_T_camera, ImageConstraints(truth, base_T_camera, 1e-4, 1e-3, &rng));
    ASSERT_TRUE(estimate.valid);
    EXPECT_EQ(estimate.steps, 120);
    EXPECT_NEAR(estimate.sigma, noise.heading_sigma, 0.25 * noise.heading_sigma) << "seed " << seed;
    EXPECT_NEAR(estimate.bias.z(), noise.heading_bias, 0.25 * noise.heading_bias) << "seed " << seed;
    EXPECT_LT(estimate.bias.head<2>().norm(), 1e-3) << "seed " << seed;
  }
}

TEST(OdometryNoiseEstimate, RecoversTheGeneratorsScaleErrorAndDistanceNoise) {
  const std::vector<Pose3> truth = TrueDrive(121, 0.03);
  OdometryNoiseOptions noise;
  noise.scale_error = 0.12;
  noise.distance_sigma = 0.06;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const OdometryTranslationEstimate estimate =
        EstimateOdometryTranslationNoise(SimulateOdometry(truth, noise, seed), truth, 0.05);
    ASSERT_TRUE(estimate.valid);
    EXPECT_NEAR(estimate.scale_error, noise.scale_error, 0.25 * noise.scale_error) << "seed " << seed;
    EXPECT_NEAR(estimate.distance_sigma, noise.distance_sigma, 0.25 * noise.distance_sigma) << "seed " << seed;
  }
}

TEST(OdometryNoiseEstimate, TooFewPairsGiveNoEstimate) {
  const std::vector<Pose3> truth = TrueDrive(5, 0.03);
  std::mt19937 rng(1);
  EXPECT_FALSE(EstimateOdometryRotationNoise(truth, TestBaseTCamera(),
                                             ImageConstraints(truth, TestBaseTCamera(), 1e-4, 1e-3, &rng))
                   .valid);
}

TEST(OdometryNoiseEstimate, ContradictionIsAFactorOfTwoEitherWay) {
  EXPECT_FALSE(DeclaredSigmaContradicted(0.01, 0.019));
  EXPECT_TRUE(DeclaredSigmaContradicted(0.01, 0.021));
  EXPECT_TRUE(DeclaredSigmaContradicted(0.01, 0.0049));
  EXPECT_FALSE(DeclaredSigmaContradicted(0, 0.01));
}

}  // namespace
}  // namespace sfm
