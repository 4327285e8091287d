#include "backend/metrics/drift.h"

#include <glog/logging.h>

#include <cmath>
#include <limits>

#include "geometry/alignment.h"

namespace sfm {
namespace {

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

std::vector<Eigen::Vector3d> Positions(const std::vector<Pose3>& world_T_camera) {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(world_T_camera.size());
  for (const Pose3& pose : world_T_camera) positions.push_back(pose.translation);
  return positions;
}

}  // namespace

double AbsoluteTrajectoryError(const std::vector<Pose3>& world_T_camera_estimated,
                               const std::vector<Pose3>& world_T_camera_truth) {
  CHECK_EQ(world_T_camera_estimated.size(), world_T_camera_truth.size());
  if (world_T_camera_truth.empty()) return kUndefined;
  const std::vector<Eigen::Vector3d> estimated = Positions(world_T_camera_estimated);
  const std::vector<Eigen::Vector3d> truth = Positions(world_T_camera_truth);
  const Pose3 truth_T_estimated = AlignSE3(estimated, truth);
  double sum_squared = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    sum_squared += (truth[i] - truth_T_estimated * estimated[i]).squaredNorm();
  }
  return std::sqrt(sum_squared / static_cast<double>(truth.size()));
}

SimilarityTrajectoryError AbsoluteTrajectoryErrorSim3(const std::vector<Pose3>& world_T_camera_estimated,
                                                      const std::vector<Pose3>& world_T_camera_truth) {
  CHECK_EQ(world_T_camera_estimated.size(), world_T_camera_truth.size());
  if (world_T_camera_truth.empty()) return {kUndefined, kUndefined};
  const std::vector<Eigen::Vector3d> estimated = Positions(world_T_camera_estimated);
  const std::vector<Eigen::Vector3d> truth = Positions(world_T_camera_truth);
  const Similarity3 truth_S_estimated = AlignSim3(estimated, truth);
  double sum_squared = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    sum_squared += (truth[i] - truth_S_estimated * estimated[i]).squaredNorm();
  }
  return {std::sqrt(sum_squared / static_cast<double>(truth.size())), truth_S_estimated.scale};
}

RelativePoseError ComputeRelativePoseError(const std::vector<Pose3>& world_T_camera_estimated,
                                           const std::vector<Pose3>& world_T_camera_truth) {
  CHECK_EQ(world_T_camera_estimated.size(), world_T_camera_truth.size());
  const size_t n = world_T_camera_truth.size();
  if (n < 2) return {kUndefined, kUndefined};
  double sum_squared_translation = 0;
  double sum_squared_angle = 0;
  for (size_t i = 0; i + 1 < n; ++i) {
    const Pose3 truth_motion = world_T_camera_truth[i].Inverse() * world_T_camera_truth[i + 1];
    const Pose3 estimated_motion = world_T_camera_estimated[i].Inverse() * world_T_camera_estimated[i + 1];
    const Pose3 error = truth_motion.Inverse() * estimated_motion;
    sum_squared_translation += error.translation.squaredNorm();
    const double angle = RotationAngle(error.rotation, Eigen::Quaterniond::Identity());
    sum_squared_angle += angle * angle;
  }
  const double pairs = static_cast<double>(n - 1);
  return {std::sqrt(sum_squared_translation / pairs), std::sqrt(sum_squared_angle / pairs)};
}

DriftMetrics ComputeDrift(const std::vector<Pose3>& world_T_camera_estimated,
                          const std::vector<Pose3>& world_T_camera_truth) {
  const RelativePoseError rpe = ComputeRelativePoseError(world_T_camera_estimated, world_T_camera_truth);
  const SimilarityTrajectoryError sim3 =
      AbsoluteTrajectoryErrorSim3(world_T_camera_estimated, world_T_camera_truth);
  return {AbsoluteTrajectoryError(world_T_camera_estimated, world_T_camera_truth), rpe.trans_m, rpe.rot_rad,
          sim3.ate_m, sim3.scale};
}

}  // namespace sfm
