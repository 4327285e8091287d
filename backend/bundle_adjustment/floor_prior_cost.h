// Residuals of the ground-plane (floor) prior and of the odometry's scale (docs/bundle_adjustment.md,
// "Floor prior"). A ground robot's base origin is on the floor, and the odometry's world frame has
// its z = 0 plane there; a landmark selected as lying on the floor is pulled to world z = 0, which
// with the camera's known height above the base fixes the map's scale (a single camera cannot).
// The odometry's translations are scaled by one free factor (a wheel-radius error), so that this
// scale comes from the floor and the per-frame odometry priors keep only the shape.
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "backend/bundle_adjustment/line_manifold.h"

namespace sfm {

// A point on the floor. Parameter block: [0] point 3 (world frame, metres).
// Residual (1, dimensionless): point z / sigma_m.
struct FloorPointCost {
  explicit FloorPointCost(double sigma_m) : sigma_m(sigma_m) {}

  template <typename T>
  bool operator()(const T* point, T* residuals) const {
    residuals[0] = point[2] / sigma_m;
    return true;
  }

  // Automatic derivatives (cost_functions.cc). sigma_m must be > 0.
  static ceres::CostFunction* Create(double sigma_m);

  double sigma_m;
};

// A line on the floor, held at two anchors (its segment's end-points when it was selected): the
// points of the line closest to the anchors are pulled to z = 0. Two anchors, so that the line is
// both at floor height and horizontal.
// Parameter block: [0] line 6 [qx qy qz qw w1 w2] (OrthonormalLineManifold).
// Residuals (2, dimensionless): z of the line's point nearest anchor k, over sigma_m.
struct FloorLineCost {
  FloorLineCost(const Eigen::Vector3d& anchor0, const Eigen::Vector3d& anchor1, double sigma_m)
      : anchor0(anchor0), anchor1(anchor1), sigma_m(sigma_m) {}

  template <typename T>
  bool operator()(const T* line, T* residuals) const {
    Eigen::Matrix<T, 3, 1> moment, direction;
    PluckerFromOrthonormal(line, &moment, &direction);
    const T direction_squared = direction.squaredNorm();
    if (!(direction_squared > T(0))) return false;  // a line at infinity
    // The point of the line nearest the origin, d x m / |d|^2 (Hartley & Zisserman 2003, 3.2.2),
    // then the nearest points to the anchors along the direction.
    const Eigen::Matrix<T, 3, 1> origin_point = direction.cross(moment) / direction_squared;
    const Eigen::Matrix<T, 3, 1> anchors[2] = {anchor0.cast<T>(), anchor1.cast<T>()};
    for (int k = 0; k < 2; ++k) {
      const T along = direction.dot(anchors[k] - origin_point) / direction_squared;
      residuals[k] = (origin_point.z() + along * direction.z()) / sigma_m;
    }
    return true;
  }

  // Automatic derivatives (cost_functions.cc). sigma_m must be > 0.
  static ceres::CostFunction* Create(const Eigen::Vector3d& anchor0, const Eigen::Vector3d& anchor1,
                                     double sigma_m);

  Eigen::Vector3d anchor0, anchor1;
  double sigma_m;
};

// A ground robot's base on the floor: its origin at world z = 0 and its z axis vertical, the rig
// that the floor prior assumes and checks on the odometry (FloorPriorRigProblem). Without it the
// odometry priors let the base's height and tilt wander as a random walk (the per-step rotation
// sigma holds roll and pitch as loosely as the heading), and the floor landmarks, seen from a
// camera a few millimetres too high or tilted by a milliradian, read that as scale.
// Parameter blocks: [0] rotation 4 (world_T_base [qx qy qz qw]), [1] translation 3.
// Residuals (3, dimensionless): t_z / sigma_m, and the x and y of the base's z axis in the world
// over tilt_sigma_rad (the sine of the tilt, split by the direction it leans to).
struct BaseOnFloorCost {
  BaseOnFloorCost(double sigma_m, double tilt_sigma_rad) : sigma_m(sigma_m), tilt_sigma_rad(tilt_sigma_rad) {}

  template <typename T>
  bool operator()(const T* rotation, const T* translation, T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> world_q_base(rotation);
    const Eigen::Matrix<T, 3, 1> up = world_q_base * Eigen::Matrix<T, 3, 1>(T(0), T(0), T(1));
    residuals[0] = translation[2] / sigma_m;
    residuals[1] = up.x() / tilt_sigma_rad;
    residuals[2] = up.y() / tilt_sigma_rad;
    return true;
  }

  // Automatic derivatives (cost_functions.cc). Both sigmas must be > 0.
  static ceres::CostFunction* Create(double sigma_m, double tilt_sigma_rad);

  double sigma_m, tilt_sigma_rad;
};

// The odometry's scale factor: (scale - 1) / sigma. Parameter block: [0] scale 1.
// Residual (1, dimensionless).
struct OdometryScalePriorCost {
  explicit OdometryScalePriorCost(double sigma) : sigma(sigma) {}

  template <typename T>
  bool operator()(const T* scale, T* residuals) const {
    residuals[0] = (scale[0] - T(1)) / sigma;
    return true;
  }

  // Automatic derivatives (cost_functions.cc). sigma must be > 0.
  static ceres::CostFunction* Create(double sigma);

  double sigma;
};

}  // namespace sfm
