// RelativePoseCost: its value on a hand-built perturbation, and its derivatives against numeric
// ones (ceres::GradientChecker, through the quaternion manifold the solver uses).
#include "backend/initialization/relative_pose_cost.h"

#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "backend/bundle_adjustment/pose_parameters.h"

namespace sfm {
namespace {

Pose3 RandomPose(std::mt19937* rng, double angle, double distance) {
  std::normal_distribution<double> normal;
  const Eigen::Vector3d axis = Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng)).normalized();
  const Eigen::Vector3d t(normal(*rng), normal(*rng), normal(*rng));
  return Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)), distance * t);
}

// A realistic rig: the camera looking forward from 0.2 m ahead of the base, pitched down a little.
Pose3 BaseTCamera() {
  Eigen::Matrix3d R;
  R << 0, -0.05, 0.99875, -1, 0, 0, 0, -0.99875, -0.05;
  return Pose3(Eigen::Quaterniond(R).normalized(), Eigen::Vector3d(0.2, 0, 1.0));
}

TEST(RelativePoseCost, ResidualIsTheWhitenedPerturbation) {
  const Pose3 base_T_camera = BaseTCamera();
  std::mt19937 rng(3);
  const Pose3 world_T_base_i = RandomPose(&rng, 0.3, 1), world_T_base_j = RandomPose(&rng, 0.3, 1);
  const Pose3 truth = (world_T_base_j * base_T_camera).Inverse() * (world_T_base_i * base_T_camera);
  // The measurement is the truth perturbed by xi = (omega, dt): the prediction is (Exp(omega) M_R,
  // M_t + dt), so M = (Exp(-omega) P_R, P_t - dt).
  const Eigen::Vector3d omega(0.01, -0.02, 0.005), dt(0.03, 0.0, -0.01);
  const Pose3 measured(Eigen::Quaterniond(Eigen::AngleAxisd(-omega.norm(), omega.normalized())) * truth.rotation,
                       truth.translation - dt);
  Eigen::Matrix<double, 6, 6> S = Eigen::Matrix<double, 6, 6>::Zero();
  S.diagonal() << 100, 200, 300, 10, 20, 30;
  std::unique_ptr<ceres::CostFunction> cost(RelativePoseCost::Create(base_T_camera, measured, S));
  const PoseParameters i = PoseParameters::FromPose(world_T_base_i), j = PoseParameters::FromPose(world_T_base_j);
  const double* parameters[] = {i.rotation.data(), i.translation.data(), j.rotation.data(), j.translation.data()};
  Eigen::Matrix<double, 6, 1> residuals;
  ASSERT_TRUE(cost->Evaluate(parameters, residuals.data(), nullptr));
  Eigen::Matrix<double, 6, 1> expected;
  expected << omega, dt;
  expected = S * expected;
  // Exact up to the quaternion round trip: 1e-9 of a residual of order 1.
  EXPECT_LT((residuals - expected).norm(), 1e-9) << residuals.transpose() << " vs " << expected.transpose();
}

TEST(RelativePoseCost, DerivativesMatchNumericOnes) {
  const Pose3 base_T_camera = BaseTCamera();
  std::mt19937 rng(7);
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds = {&quaternion, nullptr, &quaternion, nullptr};
  ceres::NumericDiffOptions numeric;
  numeric.ridders_relative_initial_step_size = 1e-4;
  for (int trial = 0; trial < 20; ++trial) {
    const Pose3 world_T_base_i = RandomPose(&rng, 1.0, 2), world_T_base_j = RandomPose(&rng, 1.0, 2);
    const Pose3 measured = RandomPose(&rng, 0.5, 1);
    Eigen::Matrix<double, 6, 6> S = Eigen::Matrix<double, 6, 6>::Random();
    std::unique_ptr<ceres::CostFunction> cost(RelativePoseCost::Create(base_T_camera, measured, S));
    const PoseParameters i = PoseParameters::FromPose(world_T_base_i), j = PoseParameters::FromPose(world_T_base_j);
    const double* parameters[] = {i.rotation.data(), i.translation.data(), j.rotation.data(), j.translation.data()};
    ceres::GradientChecker checker(cost.get(), &manifolds, numeric);
    ceres::GradientChecker::ProbeResults results;
    // Relative precision of the automatic derivatives against Ridders' extrapolation.
    EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results)) << "trial " << trial << ": " << results.error_log;
  }
}

}  // namespace
}  // namespace sfm
