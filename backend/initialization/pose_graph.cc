#include "backend/initialization/pose_graph.h"

#include <ceres/ceres.h>

#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <string>

#include "backend/bundle_adjustment/odometry_prior_cost.h"
#include "backend/bundle_adjustment/pose_parameters.h"
#include "backend/initialization/relative_pose_cost.h"

namespace sfm {
namespace {

// S with S^T S = information, from its eigen-decomposition (negative eigenvalues, rounding of a
// difference of two information matrices, count as zero).
Eigen::Matrix<double, 6, 6> SquareRoot(const Eigen::Matrix<double, 6, 6>& information) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(
      0.5 * (information + information.transpose()));
  const Eigen::Matrix<double, 6, 1> roots = eigen.eigenvalues().cwiseMax(0).cwiseSqrt();
  return roots.asDiagonal() * eigen.eigenvectors().transpose();
}

// The solve's start: the odometry's steps chained, each replaced by the images' where the pair
// (k, k + 1) has a constraint (rotation, and direction of travel at the odometry's length), and
// otherwise turned back by the start bias. From the odometry itself, a drift of tenths of a
// radian would make most pairs look like outliers to the Cauchy loss, which would then discard
// the very constraints that undo the drift.
std::vector<Pose3> ChainedStart(const std::vector<Pose3>& world_T_base_odometry, const Pose3& base_T_camera,
                                const std::vector<RelativePoseConstraint>& constraints,
                                const Eigen::Vector3d& rotation_bias) {
  const int n = static_cast<int>(world_T_base_odometry.size());
  std::vector<const RelativePoseConstraint*> step_constraint(n, nullptr);
  for (const RelativePoseConstraint& constraint : constraints) {
    if (constraint.frame_j == constraint.frame_i + 1) step_constraint[constraint.frame_i] = &constraint;
  }
  const Pose3 camera_T_base = base_T_camera.Inverse();
  const double bias_angle = rotation_bias.norm();
  const Eigen::Quaterniond bias_inverse =
      bias_angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(-bias_angle, rotation_bias / bias_angle))
                     : Eigen::Quaterniond::Identity();
  std::vector<Pose3> start = {world_T_base_odometry[0]};
  for (int k = 0; k + 1 < n; ++k) {
    Pose3 step = world_T_base_odometry[k].Inverse() * world_T_base_odometry[k + 1];
    if (step_constraint[k] != nullptr) {
      const Pose3 images = base_T_camera * step_constraint[k]->camera_j_T_camera_i.Inverse() * camera_T_base;
      const double length = step.translation.norm(), image_length = images.translation.norm();
      step.rotation = images.rotation;
      if (image_length > 0) step.translation = images.translation * (length / image_length);
    } else {
      step.rotation = bias_inverse * step.rotation;
    }
    start.push_back(start.back() * step);
  }
  return start;
}

}  // namespace

Status SolvePoseGraph(const std::vector<Pose3>& world_T_base_odometry, const Pose3& base_T_camera,
                      const OdometryNoise& odometry_noise, const BundleAdjustmentOptions& adjustment,
                      const std::vector<RelativePoseConstraint>& constraints, const PoseGraphOptions& options,
                      std::vector<Pose3>* world_T_base, PoseGraphSummary* summary) {
  const int n = static_cast<int>(world_T_base_odometry.size());
  *summary = PoseGraphSummary();
  *world_T_base = world_T_base_odometry;
  if (n < 2 || constraints.empty()) return Status::Ok();

  for (const RelativePoseConstraint& constraint : constraints) {
    if (!(0 <= constraint.frame_i && constraint.frame_i < constraint.frame_j && constraint.frame_j < n)) {
      return Status::Error("pose graph: constraint between frames " + std::to_string(constraint.frame_i) + " and " +
                           std::to_string(constraint.frame_j) + " out of range");
    }
  }
  std::vector<PoseParameters> poses;
  poses.reserve(n);
  for (const Pose3& pose : ChainedStart(world_T_base_odometry, base_T_camera, constraints, options.rotation_bias_start)) {
    poses.push_back(PoseParameters::FromPose(pose));
  }

  ceres::Problem problem;
  Eigen::Vector3d rotation_bias = options.rotation_bias_start;
  // The odometry's scale is the floor prior's to observe (bundle adjustment): held at 1 here.
  double odometry_scale = 1;
  for (int k = 0; k + 1 < n; ++k) {
    const Pose3 step = world_T_base_odometry[k].Inverse() * world_T_base_odometry[k + 1];
    const OdometryStepSigmas sigmas = OdometryStepSigmasFor(step.translation.norm(), odometry_noise, adjustment);
    OdometryPriorCost prior(step, odometry_noise.rotation_sigma, sigmas.along_m, sigmas.across_m);
    for (int axis = 0; axis < 3; ++axis) {
      if (options.rotation_sigmas[axis] > 0) prior.rotation_sigmas_rad[axis] = options.rotation_sigmas[axis];
    }
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<OdometryPriorCost, 6, 4, 3, 4, 3, 1, 3>(new OdometryPriorCost(prior)), nullptr,
        poses[k].rotation.data(), poses[k].translation.data(), poses[k + 1].rotation.data(),
        poses[k + 1].translation.data(), &odometry_scale, rotation_bias.data());
  }
  problem.AddResidualBlock(OdometryRotationBiasPriorCost::Create(odometry_noise.rotation_sigma), nullptr,
                           rotation_bias.data());
  problem.SetParameterBlockConstant(&odometry_scale);
  std::vector<ceres::ResidualBlockId> pair_blocks;
  for (const RelativePoseConstraint& constraint : constraints) {
    const int i = constraint.frame_i, j = constraint.frame_j;
    pair_blocks.push_back(problem.AddResidualBlock(
        RelativePoseCost::Create(base_T_camera, constraint.camera_j_T_camera_i, SquareRoot(constraint.information)),
        constraint.robust ? new ceres::CauchyLoss(options.loss_scale_sigmas) : nullptr, poses[i].rotation.data(),
        poses[i].translation.data(),
        poses[j].rotation.data(), poses[j].translation.data()));
  }
  for (PoseParameters& pose : poses) problem.SetManifold(pose.rotation.data(), new ceres::EigenQuaternionManifold);
  problem.SetParameterBlockConstant(poses[0].rotation.data());
  problem.SetParameterBlockConstant(poses[0].translation.data());

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = 1;
  ceres::Solver::Summary report;
  ceres::Solve(solver, &problem, &report);
  if (!report.IsSolutionUsable()) return Status::Error("pose graph: " + report.message);

  summary->constraints = static_cast<int>(constraints.size());
  summary->initial_cost = report.initial_cost;
  summary->final_cost = report.final_cost;
  summary->iterations = static_cast<int>(report.iterations.size());
  summary->rotation_bias = rotation_bias;
  for (size_t c = 0; c < pair_blocks.size(); ++c) {
    double cost = 0;
    Eigen::Matrix<double, 6, 1> residuals;
    problem.EvaluateResidualBlock(pair_blocks[c], /*apply_loss_function=*/false, &cost, residuals.data(), nullptr);
    if (residuals.norm() > options.loss_scale_sigmas) ++summary->constraints_rejected;
    VLOG(1) << "pose graph: pair " << constraints[c].frame_i << "-" << constraints[c].frame_j
            << " whitened residual " << residuals.transpose();
  }
  for (int k = 0; k < n; ++k) (*world_T_base)[k] = poses[k].ToPose();
  return Status::Ok();
}

}  // namespace sfm
