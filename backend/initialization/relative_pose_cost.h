// The pose graph's factor of one image pair (pose_graph.h): the relative camera pose predicted by
// two base poses against the one the pair's matches determined.
#pragma once

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/pose.h"

namespace sfm {

// Parameter blocks: world_T_base_i rotation [qx qy qz qw] (4), translation (3), and the same of
// frame j. With world_T_camera = world_T_base * base_T_camera, the predicted pose is
// P = camera_j_T_world * world_T_camera_i and the measured one M = camera_j_T_camera_i. The error
// xi = (omega, dt) follows PairGeometry's perturbation: P_R = Exp(omega) M_R, P_t = M_t + dt.
// Residuals (6): S xi, with S^T S the measurement's information (S = its upper Cholesky factor,
// or any square root).
struct RelativePoseCost {
  RelativePoseCost(const Pose3& base_T_camera, const Pose3& camera_j_T_camera_i,
                   const Eigen::Matrix<double, 6, 6>& sqrt_information)
      : base_q_camera(base_T_camera.rotation.normalized()),
        base_t_camera(base_T_camera.translation),
        measured_rotation_inverse(camera_j_T_camera_i.rotation.conjugate().normalized()),
        measured_translation(camera_j_T_camera_i.translation),
        sqrt_information(sqrt_information) {}

  template <typename T>
  bool operator()(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                  T* residuals) const {
    using Quaternion = Eigen::Quaternion<T>;
    using Vector3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Quaternion> world_q_base_i(rotation_i), world_q_base_j(rotation_j);
    const Eigen::Map<const Vector3> world_t_base_i(translation_i), world_t_base_j(translation_j);
    const Quaternion base_q_cam = base_q_camera.cast<T>();
    const Vector3 base_t_cam = base_t_camera.cast<T>();
    const Quaternion world_q_cam_i = world_q_base_i * base_q_cam;
    const Quaternion world_q_cam_j = world_q_base_j * base_q_cam;
    const Vector3 world_t_cam_i = world_q_base_i * base_t_cam + world_t_base_i;
    const Vector3 world_t_cam_j = world_q_base_j * base_t_cam + world_t_base_j;
    const Quaternion cam_j_q_world = world_q_cam_j.conjugate();
    const Quaternion predicted_rotation = cam_j_q_world * world_q_cam_i;
    const Vector3 predicted_translation = cam_j_q_world * (world_t_cam_i - world_t_cam_j);
    const Quaternion error_rotation = predicted_rotation * measured_rotation_inverse.cast<T>();
    // ceres::QuaternionToAngleAxis takes [w x y z].
    const T error_wxyz[4] = {error_rotation.w(), error_rotation.x(), error_rotation.y(), error_rotation.z()};
    Eigen::Matrix<T, 6, 1> error;
    ceres::QuaternionToAngleAxis(error_wxyz, error.data());
    error.template tail<3>() = predicted_translation - measured_translation.cast<T>();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> whitened(residuals);
    whitened = sqrt_information.cast<T>() * error;
    return true;
  }

  static ceres::CostFunction* Create(const Pose3& base_T_camera, const Pose3& camera_j_T_camera_i,
                                     const Eigen::Matrix<double, 6, 6>& sqrt_information) {
    return new ceres::AutoDiffCostFunction<RelativePoseCost, 6, 4, 3, 4, 3>(
        new RelativePoseCost(base_T_camera, camera_j_T_camera_i, sqrt_information));
  }

  Eigen::Quaterniond base_q_camera;
  Eigen::Vector3d base_t_camera;
  Eigen::Quaterniond measured_rotation_inverse;
  Eigen::Vector3d measured_translation;
  Eigen::Matrix<double, 6, 6> sqrt_information;
};

}  // namespace sfm
