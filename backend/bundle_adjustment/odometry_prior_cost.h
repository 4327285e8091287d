// Relative-pose prior between two frames from the wheel odometry.
//
// With the odometry's motion M = odom_i^-1 odom_j and the estimated motion X = est_i^-1 est_j
// (both base_i_T_base_j), the error is E = M^-1 X (identity when the estimate moves exactly as
// the odometry says). Residuals: E's rotation as an angle-axis vector divided by
// rotation_sigma_rad, then E's translation whitened by the odometry noise model: its component
// along the measured step divided by along_sigma_m, its components across the step by
// across_sigma_m. The two differ because a wheel odometry measures a step's length with its
// distance error and the step's direction with its heading error (OdometryStepSigmas;
// docs/bundle_adjustment.md, "Odometry prior").
// OdometryPriorWithScaleCost scales the measured translation by a free factor (the floor prior).
// The *BiasCost variants add a constant rotation increment per step b shared by every step (a
// wheel-base error or an unequal wheel pair turns the odometry by the same small angle every
// frame): the odometry's rotation is predicted as Exp(b) X_R (docs/bundle_adjustment.md,
// "Odometry rotation bias").
#pragma once

#include <ceres/cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"

namespace sfm {

// Standard deviations of an odometry step's translation error (metres), along the measured step
// and across it.
struct OdometryStepSigmas {
  double along_m = 0;
  double across_m = 0;
};

// The sigmas of a step of `distance_m` (docs/bundle_adjustment.md, "Odometry prior"), with
// d = max(distance_m, options.odometry_min_distance_m):
//   along  = noise.translation_sigma * d
//   across = noise.rotation_sigma * d  (kAlongAcross: the step's direction is known to the heading's
//            accuracy, so a sideways error is the heading error times the distance), or
//            noise.translation_sigma * d (kIsotropic, the model before the distinction).
// A step shorter than the floor gets one sigma in every direction, the larger of the two.
OdometryStepSigmas OdometryStepSigmasFor(double distance_m, const OdometryNoise& noise,
                                         const BundleAdjustmentOptions& options);

// Parameter blocks:
//   [0] world_T_base_i rotation     4  [qx qy qz qw] (ceres::EigenQuaternionManifold)
//   [1] world_T_base_i translation  3  metres
//   [2] world_T_base_j rotation     4  [qx qy qz qw]
//   [3] world_T_base_j translation  3  metres
// Residuals (6, dimensionless): angle-axis(E) / rotation_sigma_rad (3), W trans(E) (3), with W the
// square root of the translation's information in base_j as measured:
//   W = u u^T / along_sigma_m + (I - u u^T) / across_sigma_m,  u = the measured step's direction in base_j
// (W = I / along_sigma_m for a step of zero length, whose direction is undefined; then the two
// sigmas must be equal). Equal sigmas give the isotropic prior |trans(E)| / sigma.
struct OdometryPriorCost {
  OdometryPriorCost(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad, double along_sigma_m,
                    double across_sigma_m)
      : measured_rotation_inverse(base_i_T_base_j_odometry.rotation.conjugate().normalized()),
        measured_translation(base_i_T_base_j_odometry.translation),
        rotation_sigma_rad(rotation_sigma_rad),
        translation_whitening(TranslationWhitening(measured_rotation_inverse * measured_translation, along_sigma_m,
                                                   across_sigma_m)) {}

  // The isotropic prior: one sigma in every direction.
  OdometryPriorCost(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad, double translation_sigma_m)
      : OdometryPriorCost(base_i_T_base_j_odometry, rotation_sigma_rad, translation_sigma_m, translation_sigma_m) {}

  // W above for a step `step` (any frame; W is in the same frame).
  static Eigen::Matrix3d TranslationWhitening(const Eigen::Vector3d& step, double along_sigma_m,
                                              double across_sigma_m) {
    const double length = step.norm();
    if (!(length > 0)) return Eigen::Matrix3d::Identity() / along_sigma_m;
    const Eigen::Vector3d u = step / length;
    const Eigen::Matrix3d along = u * u.transpose();
    return along / along_sigma_m + (Eigen::Matrix3d::Identity() - along) / across_sigma_m;
  }

  template <typename T>
  bool operator()(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                  T* residuals) const {
    return Residuals(rotation_i, translation_i, rotation_j, translation_j, T(1),
                     static_cast<const T*>(nullptr), residuals);
  }

  // The residuals with the measured translation multiplied by `scale` (the odometry's scale
  // factor of the floor prior, OdometryPriorWithScaleCost; 1 without it) and, when
  // `rotation_bias` is not null, the estimated rotation turned by the odometry's rotation bias b
  // (angle-axis, base_i) before it is compared with the measurement: E_R = M_R^-1 Exp(b) X_R.
  // Left multiplication in base_i because the odometry models add their bias that way
  // (sequences/generator/odometry_noise.h: R' = Rz(bias + noise) R; the importer's
  // camera_odometry_noise.h: R' = Exp(bias e_y + noise) R). The translation is not turned: both
  // models leave the measured step's translation in base_i unrotated by the bias.
  template <typename T>
  bool Residuals(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                 const T& scale, const T* rotation_bias, T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q_i(rotation_i), q_j(rotation_j);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t_i(translation_i), t_j(translation_j);
    const Eigen::Quaternion<T> q_i_inverse = q_i.conjugate();
    // X = est_i^-1 est_j, then E = M^-1 X = (M_R^T X_R, M_R^T (X_t - M_t)).
    Eigen::Quaternion<T> estimated_rotation = q_i_inverse * q_j;
    if (rotation_bias != nullptr) {
      T bias_wxyz[4];
      ceres::AngleAxisToQuaternion(rotation_bias, bias_wxyz);
      estimated_rotation =
          Eigen::Quaternion<T>(bias_wxyz[0], bias_wxyz[1], bias_wxyz[2], bias_wxyz[3]) * estimated_rotation;
    }
    const Eigen::Matrix<T, 3, 1> estimated_translation = q_i_inverse * (t_j - t_i);
    const Eigen::Quaternion<T> measured_inverse = measured_rotation_inverse.cast<T>();
    const Eigen::Quaternion<T> error_rotation = measured_inverse * estimated_rotation;
    const Eigen::Matrix<T, 3, 1> error_translation =
        measured_inverse * (estimated_translation - scale * measured_translation.cast<T>());
    const Eigen::Matrix<T, 3, 1> whitened_translation = translation_whitening.cast<T>() * error_translation;
    // ceres::QuaternionToAngleAxis takes [w x y z].
    const T error_wxyz[4] = {error_rotation.w(), error_rotation.x(), error_rotation.y(), error_rotation.z()};
    T angle_axis[3];
    ceres::QuaternionToAngleAxis(error_wxyz, angle_axis);
    for (int k = 0; k < 3; ++k) {
      residuals[k] = angle_axis[k] / rotation_sigma_rad;
      residuals[3 + k] = whitened_translation[k];
    }
    return true;
  }

  // An automatic-derivative cost function (defined in cost_functions.cc). Every sigma must be > 0;
  // for a step of zero length the two translation sigmas must be equal.
  static ceres::CostFunction* Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                     double along_sigma_m, double across_sigma_m);
  // The isotropic prior.
  static ceres::CostFunction* Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                     double translation_sigma_m) {
    return Create(base_i_T_base_j_odometry, rotation_sigma_rad, translation_sigma_m, translation_sigma_m);
  }

  Eigen::Quaterniond measured_rotation_inverse;
  Eigen::Vector3d measured_translation;
  double rotation_sigma_rad;
  Eigen::Matrix3d translation_whitening;
};

// The same prior with the odometry's translations scaled by a free factor (a wheel-radius error),
// for the floor prior (floor_prior_cost.h), which observes the scale.
// Parameter blocks: the four of OdometryPriorCost, then [4] scale 1 (dimensionless).
struct OdometryPriorWithScaleCost {
  explicit OdometryPriorWithScaleCost(const OdometryPriorCost& prior) : prior(prior) {}

  template <typename T>
  bool operator()(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                  const T* scale, T* residuals) const {
    return prior.Residuals(rotation_i, translation_i, rotation_j, translation_j, scale[0],
                           static_cast<const T*>(nullptr), residuals);
  }

  // Automatic derivatives (cost_functions.cc). As OdometryPriorCost::Create.
  static ceres::CostFunction* Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                     double along_sigma_m, double across_sigma_m);
  static ceres::CostFunction* Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                     double translation_sigma_m) {
    return Create(base_i_T_base_j_odometry, rotation_sigma_rad, translation_sigma_m, translation_sigma_m);
  }

  OdometryPriorCost prior;
};

// The prior with the odometry's rotation bias b (Residuals above).
// Parameter blocks: the four of OdometryPriorCost, then [4] b 3 (rad, angle-axis in base_i).
struct OdometryPriorWithBiasCost {
  explicit OdometryPriorWithBiasCost(const OdometryPriorCost& prior) : prior(prior) {}

  template <typename T>
  bool operator()(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                  const T* rotation_bias, T* residuals) const {
    return prior.Residuals(rotation_i, translation_i, rotation_j, translation_j, T(1), rotation_bias,
                           residuals);
  }

  // Automatic derivatives (cost_functions.cc). As OdometryPriorCost::Create.
  static ceres::CostFunction* Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                     double along_sigma_m, double across_sigma_m);

  OdometryPriorCost prior;
};

// The prior with both the scale factor and the rotation bias.
// Parameter blocks: the four of OdometryPriorCost, [4] scale 1, [5] b 3.
struct OdometryPriorWithScaleAndBiasCost {
  explicit OdometryPriorWithScaleAndBiasCost(const OdometryPriorCost& prior) : prior(prior) {}

  template <typename T>
  bool operator()(const T* rotation_i, const T* translation_i, const T* rotation_j, const T* translation_j,
                  const T* scale, const T* rotation_bias, T* residuals) const {
    return prior.Residuals(rotation_i, translation_i, rotation_j, translation_j, scale[0], rotation_bias,
                           residuals);
  }

  // Automatic derivatives (cost_functions.cc). As OdometryPriorCost::Create.
  static ceres::CostFunction* Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                     double along_sigma_m, double across_sigma_m);

  OdometryPriorCost prior;
};

// Zero-mean Gaussian prior on the odometry's rotation bias: b / sigma_rad (3 residuals,
// dimensionless). Parameter block: [0] b 3 (rad).
struct OdometryRotationBiasPriorCost {
  explicit OdometryRotationBiasPriorCost(double sigma_rad) : sigma_rad(sigma_rad) {}

  template <typename T>
  bool operator()(const T* rotation_bias, T* residuals) const {
    for (int k = 0; k < 3; ++k) residuals[k] = rotation_bias[k] / sigma_rad;
    return true;
  }

  // Automatic derivatives (cost_functions.cc). sigma_rad must be > 0.
  static ceres::CostFunction* Create(double sigma_rad);

  double sigma_rad;
};

}  // namespace sfm
