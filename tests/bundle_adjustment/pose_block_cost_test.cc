// PoseBlockCost: a cost function on (rotation, translation) pairs shown to Ceres as one 7-number
// pose block. Its values and Jacobian entries must be the wrapped function's, copied (compared
// exactly), and its derivatives must pass ceres::GradientChecker through PoseManifold.
#include "backend/bundle_adjustment/pose_block_cost.h"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <random>
#include <vector>

#include "backend/bundle_adjustment/line_manifold.h"
#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/odometry_prior_cost.h"

namespace sfm {
namespace {

// One pose as PoseBlockCost's block: [qx qy qz qw tx ty tz].
std::array<double, 7> PoseBlock(const Pose3& pose) {
  const PoseParameters parameters = PoseParameters::FromPose(pose);
  std::array<double, 7> block;
  std::copy(parameters.rotation.begin(), parameters.rotation.end(), block.begin());
  std::copy(parameters.translation.begin(), parameters.translation.end(), block.begin() + 4);
  return block;
}

Pose3 SomePose(double angle, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  return Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), t);
}

ceres::CostFunction* OdometryStep() {
  const Pose3 motion = SomePose(0.05, {0.1, 0.2, 1}, {0.3, 0.02, 0.01});
  return OdometryPriorCost::Create(motion, 0.002, 0.01, 0.004);
}

// The odometry prior (6 residuals; blocks 4, 3, 4, 3, 1, 3): as one pose block
// each, the blocks are 7, 7, 1, 3, and every residual and Jacobian entry equals the wrapped
// function's, also with the Jacobian of one pose not asked for (a pose Ceres holds constant).
// Tolerance 0: the entries are copied.
TEST(PoseBlockCostTest, SameResidualsAndJacobiansAsThePairOfBlocks) {
  std::unique_ptr<ceres::CostFunction> inner(OdometryStep());
  PoseBlockCost outer(OdometryStep(), {0, 2});
  EXPECT_EQ(outer.parameter_block_sizes(), (std::vector<int32_t>{7, 7, 1, 3}));
  EXPECT_EQ(outer.num_residuals(), 6);

  const std::array<double, 7> pose_i = PoseBlock(SomePose(0.3, {0, 0, 1}, {1, 2, 0}));
  const std::array<double, 7> pose_j = PoseBlock(SomePose(0.36, {0.01, 0, 1}, {1.25, 2.2, 0.01}));
  const double scale = 1.02;
  const std::array<double, 3> bias = {0.0001, -0.0002, 0.001};
  const double* inner_parameters[] = {pose_i.data(), pose_i.data() + 4, pose_j.data(), pose_j.data() + 4,
                                      &scale,        bias.data()};
  const double* outer_parameters[] = {pose_i.data(), pose_j.data(), &scale, bias.data()};

  std::array<double, 6> r_inner, r_outer;
  std::array<double, 6 * 4> J_qi, J_qj;
  std::array<double, 6 * 3> J_ti, J_tj, J_b;
  std::array<double, 6> J_s;
  double* inner_jacobians[] = {J_qi.data(), J_ti.data(), J_qj.data(), J_tj.data(), J_s.data(), J_b.data()};
  ASSERT_TRUE(inner->Evaluate(inner_parameters, r_inner.data(), inner_jacobians));

  for (const bool first_pose_held : {false, true}) {
    std::array<double, 6 * 7> O_i, O_j;
    std::array<double, 6 * 3> O_b;
    std::array<double, 6> O_s;
    O_i.fill(-7);  // must stay untouched when not asked for
    double* outer_jacobians[] = {first_pose_held ? nullptr : O_i.data(), O_j.data(), O_s.data(), O_b.data()};
    ASSERT_TRUE(outer.Evaluate(outer_parameters, r_outer.data(), outer_jacobians));
    EXPECT_EQ(r_outer, r_inner);
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 7; ++c) {
        const double qi = c < 4 ? J_qi[4 * r + c] : J_ti[3 * r + c - 4];
        const double qj = c < 4 ? J_qj[4 * r + c] : J_tj[3 * r + c - 4];
        EXPECT_EQ(O_i[7 * r + c], first_pose_held ? -7 : qi) << "row " << r << " column " << c;
        EXPECT_EQ(O_j[7 * r + c], qj) << "row " << r << " column " << c;
      }
      EXPECT_EQ(O_s[r], J_s[r]);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(O_b[3 * r + c], J_b[3 * r + c]);
    }
  }
  // Residuals alone (automatic derivatives round them differently with and without Jacobians:
  // compared with the wrapped function's, also alone).
  ASSERT_TRUE(inner->Evaluate(inner_parameters, r_inner.data(), nullptr));
  ASSERT_TRUE(outer.Evaluate(outer_parameters, r_outer.data(), nullptr));
  EXPECT_EQ(r_outer, r_inner);
}

// A failed evaluation of the wrapped function (a line through the camera centre) fails the wrapper.
TEST(PoseBlockCostTest, FailureIsPassedOn) {
  const CameraModel camera(Pose3::Identity(), 500, 500, 320, 240);
  PoseBlockCost cost(LineReprojectionCost::Create(camera, {100, 100}, {200, 200}), {0});
  const std::array<double, 7> pose = PoseBlock(Pose3::Identity());
  const OrthonormalLine line = OrthonormalLineFromPointDirection({0, 0, 0}, {0, 0, 1});  // through the centre
  const double* parameters[] = {pose.data(), line.data()};
  std::array<double, 2> r;
  EXPECT_FALSE(cost.Evaluate(parameters, r.data(), nullptr));
}

// GradientChecker through PoseManifold (quaternion x R^3) on the wrapped line residual and
// odometry prior at random poses: relative precision 1e-7 against Ridders's extrapolation (the
// tolerance of cost_functions_test.cc's checks of the wrapped functions).
TEST(PoseBlockCostTest, GradientCheck) {
  std::mt19937 engine(4321);
  auto uniform = [&](double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(engine);
  };
  auto vector = [&](double low, double high) {
    return Eigen::Vector3d(uniform(low, high), uniform(low, high), uniform(low, high));
  };
  ceres::NumericDiffOptions ridders;
  ridders.ridders_relative_initial_step_size = 1e-4;
  PoseManifold pose_manifold;
  OrthonormalLineManifold line_manifold;
  const CameraModel camera(SomePose(-M_PI / 2, {1, 0, 0}, {0.2, 0, 1}), 500, 500, 320, 240);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose3 world_T_base = SomePose(uniform(0, M_PI), vector(-1, 1), vector(-3, 3));
    const Pose3 world_T_camera = world_T_base * SomePose(-M_PI / 2, {1, 0, 0}, {0.2, 0, 1});
    const Eigen::Vector3d a = world_T_camera * Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(2, 6));
    const Eigen::Vector3d b = world_T_camera * Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(2, 6));
    const OrthonormalLine line = OrthonormalLineFromPointDirection(a, (b - a).normalized());
    const std::array<double, 7> pose = PoseBlock(world_T_base);
    {
      PoseBlockCost cost(LineReprojectionCost::Create(camera, {uniform(0, 640), uniform(0, 480)},
                                                      {uniform(0, 640), uniform(0, 480)}),
                         {0});
      const std::vector<const ceres::Manifold*> manifolds = {&pose_manifold, &line_manifold};
      const double* parameters[] = {pose.data(), line.data()};
      ceres::GradientChecker checker(&cost, &manifolds, ridders);
      ceres::GradientChecker::ProbeResults results;
      EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results))
          << "line, trial " << trial << ": " << results.error_log;
    }
    {
      PoseBlockCost cost(OdometryStep(), {0, 2});
      const std::array<double, 7> next = PoseBlock(world_T_base * SomePose(0.05, {0, 0, 1}, {0.3, 0, 0}));
      const double scale = uniform(0.97, 1.03);
      const Eigen::Vector3d bias = vector(-0.001, 0.001);
      const std::vector<const ceres::Manifold*> manifolds = {&pose_manifold, &pose_manifold, nullptr,
                                                             nullptr};
      const double* parameters[] = {pose.data(), next.data(), &scale, bias.data()};
      ceres::GradientChecker checker(&cost, &manifolds, ridders);
      ceres::GradientChecker::ProbeResults results;
      EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results))
          << "odometry, trial " << trial << ": " << results.error_log;
    }
  }
}

}  // namespace
}  // namespace sfm
