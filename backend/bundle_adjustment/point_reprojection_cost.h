// Reprojection error of a 3D point in one frame (Hartley & Zisserman 2003, section 18.1):
// the observed undistorted pixel minus the projection K [R | t] of the point, with the camera
// pose world_T_camera = world_T_base * base_T_camera.
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Core>

#include "backend/bundle_adjustment/pose_parameters.h"

namespace sfm {

// Parameter blocks:
//   [0] world_T_base rotation     4  [qx qy qz qw] (ceres::EigenQuaternionManifold)
//   [1] world_T_base translation  3  metres
//   [2] point                     3  world frame, metres
// Residuals (2): sqrt_information (projection - observed), the pixel error whitened by the
// junction location's precision (LocationSqrtInformation; the identity for a right-angle corner,
// where it is the pixel error, x then y). Returns false for a point at or behind the camera centre
// (depth <= 0), which the solver treats as a rejected step.
struct PointReprojectionCost {
  PointReprojectionCost(const CameraModel& camera, const Eigen::Vector2d& observed_px,
                        const Eigen::Matrix2d& sqrt_information = Eigen::Matrix2d::Identity())
      : camera(camera), observed_px(observed_px), sqrt_information(sqrt_information) {}

  template <typename T>
  bool operator()(const T* rotation, const T* translation, const T* point, T* residuals) const {
    const Eigen::Matrix<T, 3, 1> p_world(point[0], point[1], point[2]);
    const Eigen::Matrix<T, 3, 1> p_camera =
        camera.camera_R_base.cast<T>() * WorldToBase(rotation, translation, p_world) +
        camera.camera_t_base.cast<T>();
    if (!(p_camera.z() > T(0))) return false;
    const T r0 = camera.fx * p_camera.x() / p_camera.z() + camera.cx - observed_px.x();
    const T r1 = camera.fy * p_camera.y() / p_camera.z() + camera.cy - observed_px.y();
    residuals[0] = sqrt_information(0, 0) * r0 + sqrt_information(0, 1) * r1;
    residuals[1] = sqrt_information(1, 0) * r0 + sqrt_information(1, 1) * r1;
    return true;
  }

  // An automatic-derivative cost function (defined in cost_functions.cc, the one translation unit
  // that instantiates the Jet code).
  static ceres::CostFunction* Create(const CameraModel& camera, const Eigen::Vector2d& observed_px,
                                     const Eigen::Matrix2d& sqrt_information = Eigen::Matrix2d::Identity());

  CameraModel camera;
  Eigen::Vector2d observed_px;
  Eigen::Matrix2d sqrt_information;
};

}  // namespace sfm
