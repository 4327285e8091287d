#include "geometry/pose.h"

#include <cmath>

namespace sfm {

Pose3 Pose3::FromMatrix4(const Eigen::Matrix4d& T) {
  return Pose3(Eigen::Quaterniond(Eigen::Matrix3d(T.topLeftCorner<3, 3>())).normalized(),
               Eigen::Vector3d(T.topRightCorner<3, 1>()));
}

Eigen::Matrix4d Pose3::Matrix4() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = RotationMatrix();
  T.topRightCorner<3, 1>() = translation;
  return T;
}

Eigen::Matrix<double, 3, 4> Pose3::Matrix3x4() const { return Matrix4().topRows<3>(); }

Pose3 Pose3::Inverse() const {
  const Eigen::Quaterniond inverse_rotation = rotation.conjugate();
  return Pose3(inverse_rotation, -(inverse_rotation * translation));
}

Pose3 Pose3::operator*(const Pose3& b_T_c) const {
  return Pose3((rotation * b_T_c.rotation).normalized(), rotation * b_T_c.translation + translation);
}

Eigen::Vector3d Pose3::operator*(const Eigen::Vector3d& p_b) const { return rotation * p_b + translation; }

double RotationAngle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b);
}

Pose3 InterpolatePose(const Pose3& a, const Pose3& b, double fraction) {
  // Eigen's slerp takes the shorter arc (it flips the sign of a quaternion on the far hemisphere);
  // it blends linearly when the two are nearly equal, hence the normalisation.
  return Pose3(a.rotation.slerp(fraction, b.rotation).normalized(),
               a.translation + fraction * (b.translation - a.translation));
}

}  // namespace sfm
