// The residuals of the self-calibrating refit (shared_camera_refit.h), as Ceres functors (automatic
// derivatives), in a header of their own so that tests can check their values and derivatives.
#pragma once

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Core>

namespace sfm {

// The scale gauge's residual weight, per unit of relative distance: a 1 % change of the first-to-
// last centre distance costs as much as 1 px of reprojection error. The weight does not move the
// optimum (the distance is a pure gauge direction, so the residual is zero there whatever its
// weight); it only has to be large enough to take the gauge out of the normal equations.
inline constexpr double kScaleGaugeWeight = 100.0;

// Pixel residual of one observation: intrinsics (fx, fy, cx, cy), k1, pose (Pose6), point (3).
struct RefitReprojectionCost {
  explicit RefitReprojectionCost(const Eigen::Vector2d& pixel) : pixel(pixel) {}

  template <typename T>
  bool operator()(const T* intrinsics, const T* k1, const T* pose, const T* point, T* residual) const {
    T p[3];
    ceres::AngleAxisRotatePoint(pose, point, p);
    for (int i = 0; i < 3; ++i) p[i] += pose[3 + i];
    const T x = p[0] / p[2], y = p[1] / p[2];
    const T radial = T(1) + k1[0] * (x * x + y * y);
    residual[0] = intrinsics[0] * x * radial + intrinsics[2] - T(pixel.x());
    residual[1] = intrinsics[1] * y * radial + intrinsics[3] - T(pixel.y());
    return true;
  }

  Eigen::Vector2d pixel;
};

// Holds the distance of a camera's centre from the (fixed) first centre at its start value.
struct RefitCentreDistanceCost {
  RefitCentreDistanceCost(const Eigen::Vector3d& first_centre, double distance)
      : first_centre(first_centre), distance(distance) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    // C = -R^T t: rotate -t by the inverse angle-axis.
    const T inverse[3] = {-pose[0], -pose[1], -pose[2]};
    const T minus_t[3] = {-pose[3], -pose[4], -pose[5]};
    T centre[3];
    ceres::AngleAxisRotatePoint(inverse, minus_t, centre);
    T squared(0);
    for (int i = 0; i < 3; ++i) {
      const T d = centre[i] - T(first_centre[i]);
      squared += d * d;
    }
    residual[0] = T(kScaleGaugeWeight) * (ceres::sqrt(squared) / T(distance) - T(1));
    return true;
  }

  Eigen::Vector3d first_centre;
  double distance;
};

}  // namespace sfm
