// Point-to-line error of an observed line segment against the projection of a 3D line.
//
// A Plücker line (m, d) in the camera frame projects to the image line l ~ K^-T m (the line through
// the images of two of its points is (K X1) x (K X2) = det(K) K^-T (X1 x X2), and X1 x X2 is the
// line's moment; Hartley & Zisserman 2003, chapter 8, the action of a camera on lines). We use
// det(K) K^-T = [fy 0 0; 0 fx 0; -fy cx  -fx cy  fx fy] (Bartoli & Sturm 2005's line projection
// matrix for P = K [I | 0]). The residuals are the signed distances of the two observed
// end-points from l, l . (x, y, 1) / |(l0, l1)|, in pixels.
#pragma once

#include <ceres/cost_function.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <cmath>

#include "backend/bundle_adjustment/line_manifold.h"
#include "backend/bundle_adjustment/pose_parameters.h"

namespace sfm {

// Parameter blocks:
//   [0] world_T_base rotation     4  [qx qy qz qw] (ceres::EigenQuaternionManifold)
//   [1] world_T_base translation  3  metres
//   [2] line                      6  [qx qy qz qw w1 w2], world frame (OrthonormalLineManifold)
// Residuals (2, pixels): signed distance of p0, then of p1, from the projected line. Returns false
// when the line passes through the camera centre (its image is not a line).
struct LineReprojectionCost {
  LineReprojectionCost(const CameraModel& camera, const Eigen::Vector2d& p0_px, const Eigen::Vector2d& p1_px)
      : camera(camera), p0_px(p0_px), p1_px(p1_px) {}

  template <typename T>
  bool operator()(const T* rotation, const T* translation, const T* line, T* residuals) const {
    Eigen::Matrix<T, 3, 1> moment_world, direction_world, moment_base, direction_base;
    PluckerFromOrthonormal(line, &moment_world, &direction_world);
    WorldToBaseLine(rotation, translation, moment_world, direction_world, &moment_base, &direction_base);
    // camera_T_base = (R, t) maps the moment to R m + t x (R d).
    const Eigen::Matrix<T, 3, 3> R = camera.camera_R_base.cast<T>();
    const Eigen::Matrix<T, 3, 1> m =
        R * moment_base + camera.camera_t_base.cast<T>().cross(R * direction_base);
    const T l0 = camera.fy * m.x();
    const T l1 = camera.fx * m.y();
    const T l2 =
        -camera.fy * camera.cx * m.x() - camera.fx * camera.cy * m.y() + camera.fx * camera.fy * m.z();
    using std::sqrt;
    const T normal_squared = l0 * l0 + l1 * l1;
    if (!(normal_squared > T(0))) return false;
    const T inverse_norm = T(1) / sqrt(normal_squared);
    residuals[0] = (l0 * p0_px.x() + l1 * p0_px.y() + l2) * inverse_norm;
    residuals[1] = (l0 * p1_px.x() + l1 * p1_px.y() + l2) * inverse_norm;
    return true;
  }

  // The cost function the solver uses: LineReprojectionCostFunction, analytic derivatives.
  static ceres::CostFunction* Create(const CameraModel& camera, const Eigen::Vector2d& p0_px,
                                     const Eigen::Vector2d& p1_px);
  // The same residual with automatic derivatives (ceres::Jet), the reference the analytic
  // Jacobians are tested against (defined in cost_functions.cc).
  static ceres::CostFunction* CreateAutoDiff(const CameraModel& camera, const Eigen::Vector2d& p0_px,
                                             const Eigen::Vector2d& p1_px);

  CameraModel camera;
  Eigen::Vector2d p0_px;
  Eigen::Vector2d p1_px;
};

// LineReprojectionCost with analytic Jacobians in the ambient coordinates of its blocks (the
// derivatives of the very formulas the functor evaluates: Eigen's q * v = v + 2w (u x v) +
// 2 u x (u x v) for the pose's conjugate quaternion, Eigen's toRotationMatrix for U), so that they
// equal the automatic ones to rounding, in every direction, not only in the manifolds' tangents.
// Same blocks, residuals and failure as the functor. The automatic derivatives through
// ceres::Jet<double, 13> were about 45 % of the pipeline's time (docs/bundle_adjustment.md).
class LineReprojectionCostFunction : public ceres::SizedCostFunction<2, 4, 3, 6> {
 public:
  LineReprojectionCostFunction(const CameraModel& camera, const Eigen::Vector2d& p0_px,
                               const Eigen::Vector2d& p1_px);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  Eigen::Matrix3d A_;                // l = A m_c: det(K) K^-T
  Eigen::Matrix3d camera_R_base_;    // m_c = Rc m_b + B d_b
  Eigen::Matrix3d B_;                // [camera_t_base]x Rc
  Eigen::Vector3d p0_, p1_;          // homogeneous pixels
};

}  // namespace sfm
