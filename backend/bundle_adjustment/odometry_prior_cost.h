// Relative-pose prior between two frames from the wheel odometry.
//
// With the odometry's motion M = odom_i^-1 odom_j and the estimated motion X = est_i^-1 est_j
// (both base_i_T_base_j), the error is E = M^-1 X (identity when the estimate moves exactly as
// the odometry says). Residuals: E's rotation as an angle-axis vector divided by
// rotation_sigma_rad, then E's translation divided by translation_sigma_m - i.e. whitened by the
// odometry noise model (docs/bundle_adjustment.md says how the sigmas are set).
// OdometryPriorWithScaleCost scales the measured translation by a free factor (the floor prior).
#pragma once

#include <ceres/cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "frontend/geometry/pose.h"

namespace sfm {

// Parameter blocks:
//   [0] world_T_base_i rotation     4  [qx qy qz qw] (ceres::EigenQuaternionManifold)
//   [1] world_T_base_i translation  3  metres
//   [2] world_T_base_j rotation     4  [qx qy qz qw]
//   [3] world_T_base_j translation  3  metres
// Residuals (6, dimensionless): angle-axis(E) / rotation_sigma_rad (3), trans(E) / translation_sigma_m (3).
struct OdometryPriorCost {
  OdometryPriorCost(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                    double translation_sigma_m)
      : measured_rotation_inverse(base_i_T_base_j_odometry.rotation.conjugate().normalized()),
        measured_translation(base_i_T_base_j_odometry.translation),
        rotation_sigma_rad(rotation_sigma_rad),
        translation_sigma_m(translation_sigma_m) {}

  template <typename T>
  bool operator()(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                  T* residuals) const {
    return Residuals(rotation_i, translation_i, rotation_j, translation_j, T(1), residuals);
  }

  // The residuals with the measured translation multiplied by `scale` (the odometry's scale
  // factor of the floor prior, OdometryPriorWithScaleCost; 1 without it).
  template <typename T>
  bool Residuals(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                 const T& scale, T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q_i(rotation_i), q_j(rotation_j);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t_i(translation_i), t_j(translation_j);
    const Eigen::Quaternion<T> q_i_inverse = q_i.conjugate();
    // X = est_i^-1 est_j, then E = M^-1 X = (M_R^T X_R, M_R^T (X_t - M_t)).
    const Eigen::Quaternion<T> estimated_rotation = q_i_inverse * q_j;
    const Eigen::Matrix<T, 3, 1> estimated_translation = q_i_inverse * (t_j - t_i);
    const Eigen::Quaternion<T> measured_inverse = measured_rotation_inverse.cast<T>();
    const Eigen::Quaternion<T> error_rotation = measured_inverse * estimated_rotation;
    const Eigen::Matrix<T, 3, 1> error_translation =
        measured_inverse * (estimated_translation - scale * measured_translation.cast<T>());
    // ceres::QuaternionToAngleAxis takes [w x y z].
    const T error_wxyz[4] = {error_rotation.w(), error_rotation.x(), error_rotation.y(), error_rotation.z()};
    T angle_axis[3];
    ceres::QuaternionToAngleAxis(error_wxyz, angle_axis);
    for (int k = 0; k < 3; ++k) {
      residuals[k] = angle_axis[k] / rotation_sigma_rad;
      residuals[3 + k] = error_translation[k] / translation_sigma_m;
    }
    return true;
  }

  // An automatic-derivative cost function (defined in cost_functions.cc). Both sigmas must be > 0.
  static ceres::CostFunction* Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                     double translation_sigma_m);

  Eigen::Quaterniond measured_rotation_inverse;
  Eigen::Vector3d measured_translation;
  double rotation_sigma_rad;
  double translation_sigma_m;
};

// The same prior with the odometry's translations scaled by a free factor (a wheel-radius error),
// for the floor prior (floor_prior_cost.h), which observes the scale.
// Parameter blocks: the four of OdometryPriorCost, then [4] scale 1 (dimensionless).
struct OdometryPriorWithScaleCost {
  explicit OdometryPriorWithScaleCost(const OdometryPriorCost& prior) : prior(prior) {}

  template <typename T>
  bool operator()(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                  const T* scale, T* residuals) const {
    return prior.Residuals(rotation_i, translation_i, rotation_j, translation_j, scale[0], residuals);
  }

  // Automatic derivatives (cost_functions.cc). Both sigmas must be > 0.
  static ceres::CostFunction* Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                     double translation_sigma_m);

  OdometryPriorCost prior;
};

}  // namespace sfm
