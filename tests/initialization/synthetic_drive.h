// A ground robot's drive for the initialization tests: true base poses on the floor, its
// odometry from the generator's noise model, and the images' relative camera poses as constraints.
#pragma once

#include <random>
#include <vector>

#include "backend/initialization/pose_graph.h"
#include "geometry/pose.h"

namespace sfm {

// A rig like the generator's: the camera 0.2 m ahead of the base and 1 m up, looking forward.
inline Pose3 TestBaseTCamera() {
  Eigen::Matrix3d R;
  R << 0, -0.05, 0.99875, -1, 0, 0, 0, -0.99875, -0.05;
  return Pose3(Eigen::Quaterniond(R).normalized(), Eigen::Vector3d(0.2, 0, 1.0));
}

// `frames` poses 0.1 m apart turning `turn_per_frame` rad to the left each frame.
inline std::vector<Pose3> TrueDrive(int frames, double turn_per_frame) {
  std::vector<Pose3> poses;
  Pose3 pose;
  const Pose3 step(Eigen::Quaterniond(Eigen::AngleAxisd(turn_per_frame, Eigen::Vector3d::UnitZ())),
                   Eigen::Vector3d(0.1, 0, 0));
  for (int k = 0; k < frames; ++k) {
    poses.push_back(pose);
    pose = pose * step;
  }
  return poses;
}

// The true relative camera pose of every pair (i, i + 1) and (i, i + 2), its rotation perturbed by
// Gaussian noise of rotation_sigma per axis and its translation's direction by direction_sigma
// (radians); the information says so: rotation_sigma on each rotation axis, and on the
// translation only across its direction (direction_sigma times the step's length), none along it
// (a monocular pair does not measure its length).
inline std::vector<RelativePoseConstraint> ImageConstraints(const std::vector<Pose3>& world_T_base,
                                                            const Pose3& base_T_camera, double rotation_sigma,
                                                            double direction_sigma, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  std::vector<RelativePoseConstraint> constraints;
  for (int i = 0; i + 1 < static_cast<int>(world_T_base.size()); ++i) {
    for (int j = i + 1; j <= i + 2 && j < static_cast<int>(world_T_base.size()); ++j) {
      RelativePoseConstraint constraint;
      constraint.frame_i = i;
      constraint.frame_j = j;
      const Pose3 truth = (world_T_base[j] * base_T_camera).Inverse() * (world_T_base[i] * base_T_camera);
      const Eigen::Vector3d omega = rotation_sigma * Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng));
      const double length = truth.translation.norm();
      const Eigen::Vector3d u = truth.translation / length;
      Eigen::Vector3d across = u.unitOrthogonal();
      const Eigen::Vector3d across2 = u.cross(across);
      const Eigen::Vector3d dt = direction_sigma * length * (normal(*rng) * across + normal(*rng) * across2);
      constraint.camera_j_T_camera_i =
          Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm(), omega.normalized())) * truth.rotation,
                truth.translation + dt);
      constraint.information.setZero();
      constraint.information.topLeftCorner<3, 3>() =
          Eigen::Matrix3d::Identity() / (rotation_sigma * rotation_sigma);
      const double across_sigma = direction_sigma * length;
      constraint.information.bottomRightCorner<3, 3>() =
          (Eigen::Matrix3d::Identity() - u * u.transpose()) / (across_sigma * across_sigma);
      constraints.push_back(constraint);
    }
  }
  return constraints;
}

}  // namespace sfm
