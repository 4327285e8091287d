// The pose of one frame as Ceres parameter blocks, the rigid transforms the cost functors apply
// to points and Plücker lines (templated so that they work with ceres::Jet), and the constant
// camera model (extrinsics on the base, K) the image functors share.
//
// A frame's pose world_T_base is two blocks:
//   rotation[4]    unit Hamilton quaternion in Eigen's storage order [qx qy qz qw]
//                  (ceres::EigenQuaternionManifold, tangent = 3),
//   translation[3] metres, world frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "geometry/pose.h"

namespace sfm {

struct PoseParameters {
  std::array<double, 4> rotation{0, 0, 0, 1};  // world_T_base, [qx qy qz qw]
  std::array<double, 3> translation{0, 0, 0};  // world_T_base, metres

  static PoseParameters FromPose(const Pose3& world_T_base);
  Pose3 ToPose() const;  // the quaternion normalised
};

inline PoseParameters PoseParameters::FromPose(const Pose3& world_T_base) {
  PoseParameters parameters;
  const Eigen::Quaterniond q = world_T_base.rotation.normalized();
  Eigen::Map<Eigen::Vector4d>(parameters.rotation.data()) = q.coeffs();
  Eigen::Map<Eigen::Vector3d>(parameters.translation.data()) = world_T_base.translation;
  return parameters;
}

inline Pose3 PoseParameters::ToPose() const {
  const Eigen::Quaterniond q(Eigen::Map<const Eigen::Vector4d>(rotation.data()));
  return Pose3(q.normalized(), Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(translation.data())));
}

// p_base = (world_T_base)^-1 p_world for the pose blocks `rotation` [qx qy qz qw] and `translation`.
template <typename T>
Eigen::Matrix<T, 3, 1> WorldToBase(const T* rotation, const T* translation,
                                   const Eigen::Matrix<T, 3, 1>& p_world) {
  const Eigen::Map<const Eigen::Quaternion<T>> world_q_base(rotation);
  const Eigen::Map<const Eigen::Matrix<T, 3, 1>> world_t_base(translation);
  return world_q_base.conjugate() * (p_world - world_t_base);
}

// The Plücker line (moment m, direction d) of the world frame expressed in the base frame, with
// the pose blocks of world_T_base. For p_base = R^T (p_world - t), the moment of the line through
// p_base with direction R^T d is R^T (p_world - t) x R^T d = R^T (m - t x d) (Plücker coordinates:
// Hartley & Zisserman 2003, section 3.2.2).
template <typename T>
void WorldToBaseLine(const T* rotation, const T* translation, const Eigen::Matrix<T, 3, 1>& moment_world,
                     const Eigen::Matrix<T, 3, 1>& direction_world, Eigen::Matrix<T, 3, 1>* moment_base,
                     Eigen::Matrix<T, 3, 1>* direction_base) {
  const Eigen::Map<const Eigen::Quaternion<T>> world_q_base(rotation);
  const Eigen::Map<const Eigen::Matrix<T, 3, 1>> world_t_base(translation);
  const Eigen::Quaternion<T> base_q_world = world_q_base.conjugate();
  *moment_base = base_q_world * (moment_world - world_t_base.cross(direction_world));
  *direction_base = base_q_world * direction_world;
}

// The constant extrinsics camera_T_base = (base_T_camera)^-1 and the pinhole intrinsics (K only)
// that the image cost functors share.
struct CameraModel {
  Eigen::Matrix3d camera_R_base = Eigen::Matrix3d::Identity();
  Eigen::Vector3d camera_t_base = Eigen::Vector3d::Zero();  // metres
  double fx = 1, fy = 1, cx = 0, cy = 0;                    // pixels

  CameraModel() = default;
  CameraModel(const Pose3& base_T_camera, double fx_px, double fy_px, double cx_px, double cy_px)
      : fx(fx_px), fy(fy_px), cx(cx_px), cy(cy_px) {
    const Pose3 camera_T_base = base_T_camera.Inverse();
    camera_R_base = camera_T_base.RotationMatrix();
    camera_t_base = camera_T_base.translation;
  }
};

}  // namespace sfm
