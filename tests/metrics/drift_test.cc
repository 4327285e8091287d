#include "backend/metrics/drift.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sfm {
namespace {

// A wandering camera trajectory: random headings and steps of about half a metre.
std::vector<Pose3> RandomTrajectory(int frames) {
  std::vector<Pose3> world_T_camera = {Pose3(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random())};
  for (int i = 1; i < frames; ++i) {
    const Pose3 step(Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::Random().normalized())),
                     Eigen::Vector3d::Random() * 0.5);
    world_T_camera.push_back(world_T_camera.back() * step);
  }
  return world_T_camera;
}

std::vector<Pose3> PositionsOnly(const std::vector<Eigen::Vector3d>& positions) {
  std::vector<Pose3> poses;
  for (const Eigen::Vector3d& p : positions) poses.emplace_back(Eigen::Quaterniond::Identity(), p);
  return poses;
}

TEST(DriftTest, ATrajectoryMovedRigidlyHasZeroAte) {
  const std::vector<Pose3> truth = RandomTrajectory(30);
  const Pose3 other_T_world(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(10, -20, 5));
  std::vector<Pose3> estimated;
  for (const Pose3& world_T_camera : truth) estimated.push_back(other_T_world * world_T_camera);
  EXPECT_LT(AbsoluteTrajectoryError(estimated, truth), /*max_m=*/1e-9);
  const DriftMetrics drift = ComputeDrift(estimated, truth);
  EXPECT_LT(drift.ate_m, 1e-9);
  EXPECT_LT(drift.rpe_trans_m, 1e-9);
  EXPECT_LT(drift.rpe_rot_rad, 1e-9);
}

TEST(DriftTest, AteOfAScaledCopyIsTheScaleErrorOfTheSpread) {
  // est = s * truth about the centroid: R = I, t = 0 is the best rigid fit (the cross-covariance
  // is symmetric positive semi-definite), so ATE = |s - 1| * sqrt(mean |truth_i|^2) = 0.1 * sqrt(2).
  const std::vector<Eigen::Vector3d> truth = {{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}};
  const Pose3 elsewhere(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(3, 2, 1));
  std::vector<Eigen::Vector3d> estimated;
  for (const Eigen::Vector3d& p : truth) estimated.push_back(elsewhere * (1.1 * p));
  EXPECT_NEAR(AbsoluteTrajectoryError(PositionsOnly(estimated), PositionsOnly(truth)), 0.1 * std::sqrt(2.0),
              1e-12);
}

TEST(DriftTest, AteOfASaddlePerturbationIsItsHeight) {
  // A planar cross whose arms are lifted by +d and -d: the lifts cancel in the cross-covariance,
  // which stays symmetric positive semi-definite, so the best rigid fit is the identity (the reflection
  // fix turns the flat direction the right way) and every point is off by d.
  const double d = 0.03;
  const std::vector<Eigen::Vector3d> truth = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  const std::vector<Eigen::Vector3d> estimated = {{1, 0, d}, {-1, 0, d}, {0, 1, -d}, {0, -1, -d}};
  EXPECT_NEAR(AbsoluteTrajectoryError(PositionsOnly(estimated), PositionsOnly(truth)), d, 1e-12);
}

TEST(DriftTest, RpeOfAConstantPerFrameErrorIsThatError) {
  // est_{i+1} = est_i * (truth_i^-1 truth_{i+1}) * error, so every E_i is `error`.
  const Pose3 error(Eigen::Quaterniond(Eigen::AngleAxisd(0.01, Eigen::Vector3d(1, 2, 3).normalized())),
                    Eigen::Vector3d(0.02, -0.01, 0.005));
  const std::vector<Pose3> truth = RandomTrajectory(25);
  std::vector<Pose3> estimated = {Pose3(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(7, 8, 9))};
  for (size_t i = 1; i < truth.size(); ++i) {
    estimated.push_back(estimated.back() * (truth[i - 1].Inverse() * truth[i]) * error);
  }
  const RelativePoseError rpe = ComputeRelativePoseError(estimated, truth);
  EXPECT_NEAR(rpe.trans_m, error.translation.norm(), 1e-12);
  EXPECT_NEAR(rpe.rot_rad, 0.01, 1e-12);
  const DriftMetrics drift = ComputeDrift(estimated, truth);
  EXPECT_EQ(drift.rpe_trans_m, rpe.trans_m);
  EXPECT_EQ(drift.rpe_rot_rad, rpe.rot_rad);
  EXPECT_GT(drift.ate_m, 0);
}

TEST(DriftTest, RpeIsTheRmsOverPairs) {
  // Two pairs, one exact and one with a 0.3 m error: RMSE = 0.3 / sqrt(2).
  const std::vector<Pose3> truth = PositionsOnly({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
  const std::vector<Pose3> estimated = PositionsOnly({{0, 0, 0}, {1, 0, 0}, {2.3, 0, 0}});
  EXPECT_NEAR(ComputeRelativePoseError(estimated, truth).trans_m, 0.3 / std::sqrt(2.0), 1e-12);
  EXPECT_EQ(ComputeRelativePoseError(estimated, truth).rot_rad, 0);
}

TEST(DriftTest, ShortTrajectoriesDoNotCrash) {
  const DriftMetrics none = ComputeDrift({}, {});
  EXPECT_TRUE(std::isnan(none.ate_m));
  EXPECT_TRUE(std::isnan(none.rpe_trans_m));
  EXPECT_TRUE(std::isnan(none.rpe_rot_rad));

  const std::vector<Pose3> one = PositionsOnly({{1, 2, 3}});
  const DriftMetrics single = ComputeDrift(PositionsOnly({{4, 4, 4}}), one);
  EXPECT_EQ(single.ate_m, 0);  // one position is always matched by a translation
  EXPECT_TRUE(std::isnan(single.rpe_trans_m));

  const DriftMetrics pair =
      ComputeDrift(PositionsOnly({{0, 0, 0}, {2, 0, 0}}), PositionsOnly({{0, 0, 0}, {1, 0, 0}}));
  EXPECT_NEAR(pair.ate_m, 0.5, 1e-12);  // translation-only: each end off by 0.5 m
  EXPECT_NEAR(pair.rpe_trans_m, 1.0, 1e-12);
}

TEST(DriftTest, AStraightTrajectoryIsAlignedByTranslation) {
  std::vector<Eigen::Vector3d> truth, estimated;
  for (int i = 0; i < 10; ++i) {
    truth.emplace_back(0.5 * i, 0, 0);
    estimated.emplace_back(0.5 * i + 2, 1, 0);
  }
  EXPECT_LT(AbsoluteTrajectoryError(PositionsOnly(estimated), PositionsOnly(truth)), 1e-12);
}

TEST(DriftTest, Sim3AteOfAScaledCopyIsZeroAndItsScaleIsTheInverse) {
  // The same scaled copy as above: its shape is right, so the Sim(3) ATE is 0 where the SE(3) ATE
  // is 0.1 sqrt(2), and the scale that maps it back is 1 / 1.1.
  const std::vector<Eigen::Vector3d> truth = {{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}};
  const Pose3 elsewhere(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(3, 2, 1));
  std::vector<Eigen::Vector3d> estimated;
  for (const Eigen::Vector3d& p : truth) estimated.push_back(elsewhere * (1.1 * p));
  const DriftMetrics drift = ComputeDrift(PositionsOnly(estimated), PositionsOnly(truth));
  EXPECT_NEAR(drift.ate_m, 0.1 * std::sqrt(2.0), 1e-12);
  EXPECT_LT(drift.ate_sim3_m, /*max_m=*/1e-12);
  EXPECT_NEAR(drift.sim3_scale, 1 / 1.1, 1e-12);
}

TEST(DriftTest, Sim3AteOfASaddlePerturbationIsItsHeight) {
  // The saddle above has the right spread in the plane (scale 1 is the best) and keeps its error d.
  const double d = 0.03;
  const std::vector<Eigen::Vector3d> truth = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  const std::vector<Eigen::Vector3d> estimated = {{1, 0, d}, {-1, 0, d}, {0, 1, -d}, {0, -1, -d}};
  const SimilarityTrajectoryError sim3 =
      AbsoluteTrajectoryErrorSim3(PositionsOnly(estimated), PositionsOnly(truth));
  // Scale: tr(D S) / sigma_e^2 = 1 / (1 + d^2); the residual then is d at every point to first order.
  EXPECT_NEAR(sim3.scale, 1 / (1 + d * d), 1e-12);
  EXPECT_NEAR(sim3.ate_m, std::sqrt(d * d / (1 + d * d)), 1e-12);
}

}  // namespace
}  // namespace sfm
