#include "sequences/importers/camera_odometry_noise.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace sfm {
namespace {

// A winding 3D camera path: forward along z with turns about every axis.
std::vector<Pose3> TruePath(int frames) {
  std::vector<Pose3> path;
  Pose3 pose(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
             Eigen::Vector3d(1.5, -0.25, 4));
  for (int i = 0; i < frames; ++i) {
    path.push_back(pose);
    const Pose3 step(Eigen::Quaterniond(Eigen::AngleAxisd(0.05 + 0.01 * i, Eigen::Vector3d(0.2, 1, -0.1 * i).normalized())),
                     Eigen::Vector3d(0.05 * std::sin(i), 0.02, 0.4 + 0.03 * i));
    pose = pose * step;
  }
  return path;
}

double MaxDifference(const std::vector<Pose3>& a, const std::vector<Pose3>& b) {
  double largest = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    largest = std::max(largest, (a[i].translation - b[i].translation).cwiseAbs().maxCoeff());
    largest = std::max(largest, RotationAngle(a[i].rotation, b[i].rotation));
  }
  return largest;
}

TEST(CameraOdometryNoiseTest, WithoutNoiseEqualsTruth) {
  CameraOdometryNoiseOptions options;
  options.scale_error = options.distance_sigma = options.rotation_sigma = options.rotation_bias = 0;
  const std::vector<Pose3> truth = TruePath(40);
  const std::vector<Pose3> odometry = SimulateCameraOdometry(truth, options, 7);
  ASSERT_EQ(odometry.size(), truth.size());
  EXPECT_LT(MaxDifference(odometry, truth), 1e-12);
}

TEST(CameraOdometryNoiseTest, StartsOnTruthAndIsRepeatableBitForBit) {
  const std::vector<Pose3> truth = TruePath(30);
  const CameraOdometryNoiseOptions options;
  const std::vector<Pose3> a = SimulateCameraOdometry(truth, options, 11);
  const std::vector<Pose3> b = SimulateCameraOdometry(truth, options, 11);
  const std::vector<Pose3> c = SimulateCameraOdometry(truth, options, 12);
  EXPECT_EQ(MaxDifference({a[0]}, {truth[0]}), 0.0);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].translation, b[i].translation);
    EXPECT_EQ(a[i].rotation.coeffs(), b[i].rotation.coeffs());
  }
  EXPECT_GT(MaxDifference(a, c), 1e-3);  // another seed, other noise
  EXPECT_GT(MaxDifference(a, truth), 1e-2);  // the defaults drift measurably
}

TEST(CameraOdometryNoiseTest, ScaleErrorAloneScalesEveryStep) {
  CameraOdometryNoiseOptions options;
  options.distance_sigma = options.rotation_sigma = options.rotation_bias = 0;
  options.scale_error = 0.03;
  const std::vector<Pose3> truth = TruePath(10);
  const std::vector<Pose3> odometry = SimulateCameraOdometry(truth, options, 3);
  for (size_t i = 1; i < truth.size(); ++i) {
    const Pose3 true_step = truth[i - 1].Inverse() * truth[i];
    const Pose3 odometry_step = odometry[i - 1].Inverse() * odometry[i];
    EXPECT_LT((odometry_step.translation - 1.03 * true_step.translation).norm(), 1e-12);
    EXPECT_LT(RotationAngle(odometry_step.rotation, true_step.rotation), 1e-12);
  }
}

TEST(CameraOdometryNoiseTest, BiasAloneTurnsEachStepAboutTheCameraYAxis) {
  CameraOdometryNoiseOptions options;
  options.scale_error = options.distance_sigma = options.rotation_sigma = 0;
  options.rotation_bias = 0.002;
  const std::vector<Pose3> truth = TruePath(10);
  const std::vector<Pose3> odometry = SimulateCameraOdometry(truth, options, 3);
  for (size_t i = 1; i < truth.size(); ++i) {
    const Pose3 true_step = truth[i - 1].Inverse() * truth[i];
    const Pose3 odometry_step = odometry[i - 1].Inverse() * odometry[i];
    const Eigen::AngleAxisd error(odometry_step.rotation * true_step.rotation.inverse());
    EXPECT_NEAR(error.angle(), 0.002, 1e-12);
    EXPECT_NEAR(error.axis().y(), 1.0, 1e-9);
  }
}

TEST(CameraOdometryNoiseTest, RotationNoiseHasTheStatedSigmaPerAxis) {
  CameraOdometryNoiseOptions options;
  options.scale_error = options.distance_sigma = options.rotation_bias = 0;
  options.rotation_sigma = 0.005;
  const std::vector<Pose3> truth = TruePath(2001);
  const std::vector<Pose3> odometry = SimulateCameraOdometry(truth, options, 5);
  Eigen::Vector3d sum_squares = Eigen::Vector3d::Zero();
  for (size_t i = 1; i < truth.size(); ++i) {
    const Pose3 true_step = truth[i - 1].Inverse() * truth[i];
    const Pose3 odometry_step = odometry[i - 1].Inverse() * odometry[i];
    const Eigen::AngleAxisd error(odometry_step.rotation * true_step.rotation.inverse());
    sum_squares += (error.angle() * error.axis()).cwiseAbs2();
  }
  const Eigen::Vector3d sigma = (sum_squares / 2000).cwiseSqrt();
  // 2000 draws: the sample sigma is within ~3% of the true one (3 standard errors of 1.6%).
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(sigma[axis], 0.005, 0.005 * 0.05) << axis;
}

// Scaled(3) triples every term, and with the same seed each step's error triples: the rotation
// error vector exactly (the same n2..n4, bias and sigma both x3), the length error (1 + s)(1 + d n1) - 1
// as the model predicts for the same n1. Tolerance 1e-12 (rounding only).
TEST(CameraOdometryNoiseTest, ScaledMultipliesEveryNoiseTerm) {
  const CameraOdometryNoiseOptions base;
  const CameraOdometryNoiseOptions tripled = base.Scaled(3);
  EXPECT_DOUBLE_EQ(tripled.scale_error, 3 * base.scale_error);
  EXPECT_DOUBLE_EQ(tripled.distance_sigma, 3 * base.distance_sigma);
  EXPECT_DOUBLE_EQ(tripled.rotation_sigma, 3 * base.rotation_sigma);
  EXPECT_DOUBLE_EQ(tripled.rotation_bias, 3 * base.rotation_bias);
  EXPECT_NEAR(tripled.ForCalibration().translation_sigma, 3 * base.ForCalibration().translation_sigma, 1e-15);
  EXPECT_NEAR(tripled.ForCalibration().rotation_sigma, 3 * base.ForCalibration().rotation_sigma, 1e-15);
  EXPECT_TRUE(tripled.Check().ok());

  const std::vector<Pose3> truth = TruePath(20);
  const std::vector<Pose3> once = SimulateCameraOdometry(truth, base, 4);
  const std::vector<Pose3> thrice = SimulateCameraOdometry(truth, tripled, 4);
  for (size_t i = 1; i < truth.size(); ++i) {
    const Pose3 true_step = truth[i - 1].Inverse() * truth[i];
    const Pose3 step_once = once[i - 1].Inverse() * once[i];
    const Pose3 step_thrice = thrice[i - 1].Inverse() * thrice[i];
    const Eigen::AngleAxisd error_once(step_once.rotation * true_step.rotation.inverse());
    const Eigen::AngleAxisd error_thrice(step_thrice.rotation * true_step.rotation.inverse());
    EXPECT_LT(
        (error_thrice.angle() * error_thrice.axis() - 3 * error_once.angle() * error_once.axis()).norm(),
        1e-12)
        << i;
    const double ratio_once = step_once.translation.norm() / true_step.translation.norm();
    const double n1 = (ratio_once / (1 + base.scale_error) - 1) / base.distance_sigma;
    const double ratio_thrice = step_thrice.translation.norm() / true_step.translation.norm();
    EXPECT_NEAR(ratio_thrice, (1 + tripled.scale_error) * (1 + tripled.distance_sigma * n1), 1e-12) << i;
  }
  const std::vector<Pose3> none = SimulateCameraOdometry(truth, base.Scaled(0), 4);
  EXPECT_LT(MaxDifference(none, truth), 1e-12);
}

TEST(CameraOdometryNoiseTest, CalibrationStatesTheModelAndChecksRejectBadValues) {
  CameraOdometryNoiseOptions options;
  const OdometryNoise noise = options.ForCalibration();
  EXPECT_NEAR(noise.translation_sigma, std::hypot(0.03, 0.01), 1e-15);
  EXPECT_NEAR(noise.rotation_sigma, std::hypot(0.0052, 0.0017), 1e-15);
  EXPECT_TRUE(options.Check().ok());
  options.distance_sigma = -0.1;
  EXPECT_FALSE(options.Check().ok());
  options = CameraOdometryNoiseOptions();
  options.rotation_sigma = std::nan("");
  EXPECT_FALSE(options.Check().ok());
}

}  // namespace
}  // namespace sfm
