// Pose3: a rigid transform, the one pose type of the project.
//
// Convention (written once, used everywhere): a variable named `a_T_b` maps coordinates in frame b
// into frame a, p_a = a_T_b * p_b. So `world_T_camera` is the camera's pose in the world and
// `base_T_camera` is the camera's pose on the robot base. Composition chains the frames:
// a_T_c = a_T_b * b_T_c, and (a_T_b).Inverse() = b_T_a.
// Rotations are unit Hamilton quaternions; files write them `qx qy qz qw` (TUM order).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sfm {

struct Pose3 {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // unit, Hamilton
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();          // metres

  Pose3() = default;
  Pose3(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) : rotation(q), translation(t) {}
  Pose3(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) : rotation(R), translation(t) {}

  static Pose3 Identity() { return Pose3(); }
  // From a 4x4 homogeneous matrix [R t; 0 0 0 1]; R must be a rotation (CHECKed by callers that read files).
  static Pose3 FromMatrix4(const Eigen::Matrix4d& T);

  Eigen::Matrix4d Matrix4() const;
  Eigen::Matrix3d RotationMatrix() const { return rotation.toRotationMatrix(); }
  Eigen::Matrix<double, 3, 4> Matrix3x4() const;

  Pose3 Inverse() const;
  Pose3 operator*(const Pose3& b_T_c) const;                  // a_T_b * b_T_c = a_T_c
  Eigen::Vector3d operator*(const Eigen::Vector3d& p_b) const;  // a_T_b * p_b = p_a
};

// The pose a fraction in [0, 1] of the way from a to b: translation linear, rotation by slerp (the
// shorter arc). Used where a trajectory is sampled between two of its timestamps.
Pose3 InterpolatePose(const Pose3& a, const Pose3& b, double fraction);

// Angle of the rotation between two poses, radians in [0, pi].
double RotationAngle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

}  // namespace sfm
