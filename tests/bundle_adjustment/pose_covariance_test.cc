// ComputePoseCovariance: the refined poses' first-order covariance (pose_covariance.h).
#include "backend/bundle_adjustment/pose_covariance.h"

#include <ceres/covariance.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <vector>

#include "backend/bundle_adjustment/line_manifold.h"
#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/odometry_prior_cost.h"
#include "backend/bundle_adjustment/point_reprojection_cost.h"
#include "backend/bundle_adjustment/pose_parameters.h"
#include "tests/bundle_adjustment/synthetic_room.h"

namespace sfm {
namespace {

using testing::RobotCalibration;

// With no landmark and no motion (steps below the odometry's distance floor), the poses are a
// random walk of the odometry priors alone: a step's rotation error r per axis, its translation
// error s per axis (the floor's sigma), rotation and translation decoupled. Relative to frame f0,
// views i and j share min(i - f0, j - f0) steps; the camera centre 0.2 m ahead of the base also
// moves by the rotation's error times the lever arm: trace k (3 s^2 + 2 r^2 |lever|^2).
// Protects the gauge (frame 0 fixed), the relative-pose algebra and the lever arm, to 1e-9.
TEST(PoseCovariance, OdometryAloneIsARandomWalk) {
  Calibration calibration = RobotCalibration(/*forward=*/0.2, /*height=*/1.0);
  calibration.odometry_noise.rotation_sigma = 0.002;
  calibration.odometry_noise.translation_sigma = 0.01;
  const BundleAdjustmentOptions options;
  const std::vector<Pose3> poses(30, Pose3());
  PoseCovariance covariance;
  ASSERT_TRUE(ComputePoseCovariance(calibration, poses, poses, Landmarks(), options, 0.3, &covariance).ok());
  const double r = 0.002;
  const double s = OdometryStepSigmasFor(0, calibration.odometry_noise, options).along_m;
  const double lever2 = calibration.base_T_camera.translation.squaredNorm();
  for (int f0 : {0, 5}) {
    const int k = 20 - f0;
    const Eigen::Matrix<double, 6, 6> own = covariance.Relative(20, 20, f0);
    EXPECT_NEAR((own.topLeftCorner<3, 3>().trace()), 3 * k * r * r, 1e-9);
    EXPECT_NEAR((own.bottomRightCorner<3, 3>().trace()), k * (3 * s * s + 2 * r * r * lever2), 1e-9);
    // Views 12 and 20 share 12 - f0 steps.
    const Eigen::Matrix<double, 6, 6> shared = covariance.Relative(12, 20, f0);
    EXPECT_NEAR((shared.topLeftCorner<3, 3>().trace()), 3 * (12 - f0) * r * r, 1e-9);
    EXPECT_NEAR(covariance.Relative(f0, 20, f0).norm(), 0, 1e-12);
  }
}

// The Schur complement and the tangent spaces against Ceres's own covariance (ceres::Covariance,
// dense SVD) of the same problem: points, lines (orthonormal manifold) and odometry priors, the
// first pose fixed, on a room loop of 12 frames. Every pose block to 5e-5 of the largest entry
// (measured: 7e-6, the dense SVD's rounding; a wrong tangent scale or Schur term is off by 100 %).
TEST(PoseCovariance, MatchesCeresCovariance) {
  Calibration calibration = RobotCalibration();
  calibration.odometry_noise.rotation_sigma = 0.003;
  calibration.odometry_noise.translation_sigma = 0.02;
  const BundleAdjustmentOptions options;
  const std::vector<Pose3> truth = testing::LoopTrajectory(12);
  const std::vector<Pose3> odometry = testing::MakeOdometry(truth, 0.02, 0.001, 0.002, 7);
  const testing::Observed observed = testing::Observe(testing::BoxRoom(), calibration, truth, truth, 0.3, 3);
  ASSERT_GT(observed.landmarks.points.size(), 20u);
  ASSERT_GT(observed.landmarks.lines.size(), 20u);
  const double sigma_px = 1.0;  // Ceres's residuals are in pixels: the same weights
  PoseCovariance covariance;
  ASSERT_TRUE(
      ComputePoseCovariance(calibration, odometry, truth, observed.landmarks, options, sigma_px, &covariance)
          .ok());

  const CameraModel camera(calibration.base_T_camera, calibration.camera.fx, calibration.camera.fy,
                           calibration.camera.cx, calibration.camera.cy);
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::EigenQuaternionManifold quaternion;
  OrthonormalLineManifold line_manifold;
  std::vector<PoseParameters> poses;
  for (const Pose3& pose : truth) poses.push_back(PoseParameters::FromPose(pose));
  for (PoseParameters& pose : poses) problem.AddParameterBlock(pose.rotation.data(), 4, &quaternion);
  std::vector<Eigen::Vector3d> points;
  for (const PointLandmark& point : observed.landmarks.points) points.push_back(point.position);
  for (size_t i = 0; i < points.size(); ++i) {
    for (const PointObservation& o : observed.landmarks.points[i].observations) {
      problem.AddResidualBlock(PointReprojectionCost::Create(camera, o.pixel), nullptr,
                               poses[o.frame].rotation.data(), poses[o.frame].translation.data(),
                               points[i].data());
    }
  }
  std::vector<OrthonormalLine> lines;
  for (const LineLandmark& line : observed.landmarks.lines) {
    lines.push_back(OrthonormalLineFromPointDirection(line.point, line.direction));
  }
  for (size_t i = 0; i < lines.size(); ++i) {
    problem.AddParameterBlock(lines[i].data(), 6, &line_manifold);
    for (const LineObservation& o : observed.landmarks.lines[i].observations) {
      problem.AddResidualBlock(LineReprojectionCost::Create(camera, o.p0, o.p1), nullptr,
                               poses[o.frame].rotation.data(), poses[o.frame].translation.data(),
                               lines[i].data());
    }
  }
  for (size_t f = 0; f + 1 < poses.size(); ++f) {
    const Pose3 motion = odometry[f].Inverse() * odometry[f + 1];
    const OdometryStepSigmas sigmas =
        OdometryStepSigmasFor(motion.translation.norm(), calibration.odometry_noise, options);
    problem.AddResidualBlock(OdometryPriorCost::Create(motion, calibration.odometry_noise.rotation_sigma,
                                                       sigmas.along_m, sigmas.across_m),
                             nullptr, poses[f].rotation.data(), poses[f].translation.data(),
                             poses[f + 1].rotation.data(), poses[f + 1].translation.data());
  }
  problem.SetParameterBlockConstant(poses[0].rotation.data());
  problem.SetParameterBlockConstant(poses[0].translation.data());

  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance ceres_covariance(covariance_options);
  std::vector<const double*> blocks;
  for (size_t f = 1; f < poses.size(); ++f) {
    blocks.push_back(poses[f].rotation.data());
    blocks.push_back(poses[f].translation.data());
  }
  std::vector<std::pair<const double*, const double*>> pairs;
  for (size_t a = 0; a < blocks.size(); ++a) {
    for (size_t b = a; b < blocks.size(); ++b) pairs.emplace_back(blocks[a], blocks[b]);
  }
  ASSERT_TRUE(ceres_covariance.Compute(pairs, &problem));
  const double scale = covariance.tangent.cwiseAbs().maxCoeff();
  double worst = 0;
  ASSERT_GT(scale, 0);
  for (size_t a = 0; a < blocks.size(); ++a) {
    for (size_t b = a; b < blocks.size(); ++b) {
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> expected;
      ASSERT_TRUE(ceres_covariance.GetCovarianceBlockInTangentSpace(blocks[a], blocks[b], expected.data()));
      const int row = 6 + 3 * static_cast<int>(a), column = 6 + 3 * static_cast<int>(b);
      // Ceres's quaternion tangent is half a rotation vector: its rotation rows and columns x 2.
      const double factor = (a % 2 == 0 ? 2.0 : 1.0) * (b % 2 == 0 ? 2.0 : 1.0);
      const Eigen::Matrix3d ours = covariance.tangent.block<3, 3>(row, column) / factor;
      worst = std::max(worst, (ours - expected).cwiseAbs().maxCoeff() / scale);
      EXPECT_LT((ours - expected).cwiseAbs().maxCoeff(), 5e-5 * scale) << "blocks " << a << ", " << b;
    }
  }
  std::printf("largest difference from ceres::Covariance: %.3g of the largest entry\n", worst);
}

}  // namespace
}  // namespace sfm
