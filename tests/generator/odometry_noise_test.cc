#include "sequences/generator/odometry_noise.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

double Yaw(const Pose3& pose) {
  const Eigen::Vector3d x = pose.rotation * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

// A planar path with straights and bends, 0.2 m apart, starting away from the origin.
std::vector<Pose3> Path(int frames) {
  std::vector<Pose3> poses;
  double x = 1.5, y = -0.7, yaw = 0.3;
  for (int i = 0; i < frames; ++i) {
    poses.push_back(Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(x, y, 0)));
    x += 0.2 * std::cos(yaw);
    y += 0.2 * std::sin(yaw);
    yaw += 0.05 * std::sin(i * 0.1);
  }
  return poses;
}

OdometryNoiseOptions NoNoise() {
  OdometryNoiseOptions options;
  options.scale_error = options.distance_sigma = options.heading_sigma = options.heading_bias = 0;
  return options;
}

double Travelled(const std::vector<Pose3>& poses) {
  double total = 0;
  for (size_t i = 1; i < poses.size(); ++i) total += (poses[i].translation - poses[i - 1].translation).norm();
  return total;
}

TEST(OdometryNoiseTest, WithoutNoiseOdometryIsTheTruth) {
  const std::vector<Pose3> truth = Path(60);
  const std::vector<Pose3> odometry = SimulateOdometry(truth, NoNoise(), 1);
  ASSERT_EQ(odometry.size(), truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    EXPECT_LT((odometry[i].translation - truth[i].translation).norm(), /*max_position_error_m=*/1e-12);
    EXPECT_LT(RotationAngle(odometry[i].rotation, truth[i].rotation), /*max_rotation_error_rad=*/1e-12);
  }
}

TEST(OdometryNoiseTest, ScaleErrorScalesTheDistanceOnly) {
  const std::vector<Pose3> truth = Path(60);
  OdometryNoiseOptions options = NoNoise();
  options.scale_error = 0.03;
  const std::vector<Pose3> odometry = SimulateOdometry(truth, options, 1);
  EXPECT_NEAR(Travelled(odometry) / Travelled(truth), 1.03, 1e-12);
  EXPECT_EQ(odometry[0].translation, truth[0].translation);
  for (size_t i = 0; i < truth.size(); ++i) EXPECT_LT(RotationAngle(odometry[i].rotation, truth[i].rotation), 1e-12);
}

TEST(OdometryNoiseTest, HeadingBiasAccumulatesPerFrame) {
  const std::vector<Pose3> truth = Path(60);
  OdometryNoiseOptions options = NoNoise();
  options.heading_bias = 0.002;
  const std::vector<Pose3> odometry = SimulateOdometry(truth, options, 1);
  for (size_t i = 0; i < truth.size(); ++i) {
    EXPECT_NEAR(std::remainder(Yaw(odometry[i]) - Yaw(truth[i]), 2 * kPi), 0.002 * i, 1e-12);
  }
  EXPECT_NEAR(Travelled(odometry), Travelled(truth), 1e-12);
}

TEST(OdometryNoiseTest, PerFrameNoiseHasItsSigma) {
  const int frames = 20001;
  const std::vector<Pose3> truth = Path(frames);
  OdometryNoiseOptions options = NoNoise();
  options.heading_sigma = 0.004;
  options.distance_sigma = 0.02;
  const std::vector<Pose3> odometry = SimulateOdometry(truth, options, 9);
  double heading_sum = 0, heading_sum2 = 0, distance_sum = 0, distance_sum2 = 0;
  for (int i = 1; i < frames; ++i) {
    const Pose3 true_motion = truth[i - 1].Inverse() * truth[i];
    const Pose3 odometry_motion = odometry[i - 1].Inverse() * odometry[i];
    const double dh = std::remainder(Yaw(odometry_motion) - Yaw(true_motion), 2 * kPi);
    const double dd = odometry_motion.translation.norm() / true_motion.translation.norm() - 1;
    heading_sum += dh;
    heading_sum2 += dh * dh;
    distance_sum += dd;
    distance_sum2 += dd * dd;
  }
  const int n = frames - 1;
  // Sample sigma of n = 20000 normal draws: relative standard error 0.5 %; 3 % margins.
  EXPECT_NEAR(heading_sum / n, 0, 5 * 0.004 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(heading_sum2 / n), 0.004, 0.03 * 0.004);
  EXPECT_NEAR(distance_sum / n, 0, 5 * 0.02 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(distance_sum2 / n), 0.02, 0.03 * 0.02);
}

TEST(OdometryNoiseTest, SameSeedSameOdometryAndNoisesAreIndependentStreams) {
  const std::vector<Pose3> truth = Path(50);
  OdometryNoiseOptions options;  // defaults
  const std::vector<Pose3> a = SimulateOdometry(truth, options, 4), b = SimulateOdometry(truth, options, 4);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].translation, b[i].translation);
    EXPECT_EQ(a[i].rotation.coeffs(), b[i].rotation.coeffs());
  }
  // Turning the heading noise off leaves the distance noise's numbers as they were.
  OdometryNoiseOptions distance_only = NoNoise(), both = NoNoise();
  distance_only.distance_sigma = both.distance_sigma = 0.02;
  both.heading_sigma = 0.01;
  const std::vector<Pose3> c = SimulateOdometry(truth, distance_only, 4), d = SimulateOdometry(truth, both, 4);
  for (size_t i = 1; i < truth.size(); ++i) {
    EXPECT_NEAR((c[i - 1].Inverse() * c[i]).translation.norm(), (d[i - 1].Inverse() * d[i]).translation.norm(), 1e-12);
  }
}

TEST(OdometryNoiseTest, CalibrationSigmasSummariseTheModel) {
  OdometryNoiseOptions options;
  const OdometryNoise noise = options.ForCalibration();
  EXPECT_NEAR(noise.translation_sigma, std::hypot(0.02, 0.01), 1e-15);
  EXPECT_NEAR(noise.rotation_sigma, std::hypot(0.002, 0.001), 1e-15);
  EXPECT_GT(NoNoise().ForCalibration().translation_sigma, 0);
  EXPECT_GT(NoNoise().ForCalibration().rotation_sigma, 0);
  options.scale_error = 0.7;
  EXPECT_FALSE(options.Check().ok());
}

// make_sequence --odometry_noise_scale: every term scaled, the draws unchanged, so the odometry's
// heading error grows by the factor (to 1e-9 relative: the heading error is linear in the terms).
TEST(OdometryNoiseTest, ScaledMultipliesEveryTerm) {
  OdometryNoiseOptions options;
  const OdometryNoiseOptions scaled = options.Scaled(3);
  EXPECT_DOUBLE_EQ(scaled.scale_error, 3 * options.scale_error);
  EXPECT_DOUBLE_EQ(scaled.distance_sigma, 3 * options.distance_sigma);
  EXPECT_DOUBLE_EQ(scaled.heading_sigma, 3 * options.heading_sigma);
  EXPECT_DOUBLE_EQ(scaled.heading_bias, 3 * options.heading_bias);
  const OdometryNoiseOptions same = options.Scaled(1);
  EXPECT_EQ(same.scale_error, options.scale_error);
  EXPECT_EQ(same.heading_bias, options.heading_bias);
  const std::vector<Pose3> truth = Path(60);
  const std::vector<Pose3> base = SimulateOdometry(truth, options, 7);
  const std::vector<Pose3> tripled = SimulateOdometry(truth, scaled, 7);
  const double yaw_error = Yaw(base.back()) - Yaw(truth.back());
  const double yaw_error_tripled = Yaw(tripled.back()) - Yaw(truth.back());
  ASSERT_GT(std::abs(yaw_error), 1e-3);
  EXPECT_NEAR(yaw_error_tripled / yaw_error, 3.0, 1e-9);
}

}  // namespace
}  // namespace sfm
