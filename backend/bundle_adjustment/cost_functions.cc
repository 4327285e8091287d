// The one translation unit that instantiates the automatic derivatives of the cost functors, and
// the analytic derivatives of the line residual.
#include <algorithm>

#include <ceres/autodiff_cost_function.h>
#include <glog/logging.h>

#include "backend/bundle_adjustment/floor_prior_cost.h"
#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/odometry_prior_cost.h"
#include "backend/bundle_adjustment/point_reprojection_cost.h"

namespace sfm {

ceres::CostFunction* PointReprojectionCost::Create(const CameraModel& camera,
                                                   const Eigen::Vector2d& observed_px,
                                                   const Eigen::Matrix2d& sqrt_information) {
  return new ceres::AutoDiffCostFunction<PointReprojectionCost, 2, 4, 3, 3>(
      new PointReprojectionCost(camera, observed_px, sqrt_information));
}

ceres::CostFunction* LineReprojectionCost::Create(const CameraModel& camera, const Eigen::Vector2d& p0_px,
                                                  const Eigen::Vector2d& p1_px) {
  return new LineReprojectionCostFunction(camera, p0_px, p1_px);
}

ceres::CostFunction* LineReprojectionCost::CreateAutoDiff(const CameraModel& camera,
                                                          const Eigen::Vector2d& p0_px,
                                                          const Eigen::Vector2d& p1_px) {
  return new ceres::AutoDiffCostFunction<LineReprojectionCost, 2, 4, 3, 6>(
      new LineReprojectionCost(camera, p0_px, p1_px));
}

namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

// f(v) = v + 2 w (u x v) + 2 u x (u x v) (Eigen's quaternion * vector) for the quaternion (u, w).
Eigen::Vector3d Rotate(const Eigen::Vector3d& u, double w, const Eigen::Vector3d& v) {
  const Eigen::Vector3d uv = u.cross(v);
  return v + 2 * w * uv + 2 * u.cross(uv);
}

// Its derivative df/d[u w] (3 x 4). Apart from Rotate: the solves' inner iterations and the lines
// solved alone on fixed poses ask for the line's Jacobian only, and this was a third of the
// residual's work (docs/bundle_adjustment.md).
Eigen::Matrix<double, 3, 4> RotationDerivative(const Eigen::Vector3d& u, double w, const Eigen::Vector3d& v) {
  const Eigen::Vector3d uv = u.cross(v);
  Eigen::Matrix<double, 3, 4> df_dq;
  // d(2 w u x v)/du = -2 w [v]x; d(2 u x (u x v))/du = -2 [u x v]x - 2 [u]x [v]x.
  df_dq.leftCols<3>() = -2 * w * Skew(v) - 2 * Skew(uv) - 2 * Skew(u) * Skew(v);
  df_dq.col(3) = 2 * uv;
  return df_dq;
}

}  // namespace

LineReprojectionCostFunction::LineReprojectionCostFunction(const CameraModel& camera,
                                                           const Eigen::Vector2d& p0_px,
                                                           const Eigen::Vector2d& p1_px)
    : camera_R_base_(camera.camera_R_base),
      B_(Skew(camera.camera_t_base) * camera.camera_R_base),
      p0_(p0_px.homogeneous()),
      p1_(p1_px.homogeneous()) {
  A_ << camera.fy, 0, 0, 0, camera.fx, 0, -camera.fy * camera.cx, -camera.fx * camera.cy, camera.fx * camera.fy;
}

bool LineReprojectionCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                            double** jacobians) const {
  const double* rotation = parameters[0];  // world_q_base [x y z w]
  const double* translation = parameters[1];
  const double* line = parameters[2];  // [qx qy qz qw w1 w2]

  // U's first two columns, as Eigen's toRotationMatrix computes them.
  const double x = line[0], y = line[1], z = line[2], w = line[3];
  const Eigen::Vector3d u1(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y));
  const Eigen::Vector3d u2(2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x));
  const Eigen::Vector3d moment_world = line[4] * u1;
  const Eigen::Vector3d direction_world = line[5] * u2;

  // base_q_world = conjugate: (u, w) -> (-u, w). m_b = f(a), a = m_w - t x d_w; d_b = f(d_w).
  const Eigen::Vector3d u_conj = -Eigen::Map<const Eigen::Vector3d>(rotation);
  const double w_conj = rotation[3];
  const Eigen::Map<const Eigen::Vector3d> t(translation);
  const Eigen::Vector3d a = moment_world - t.cross(direction_world);
  const Eigen::Vector3d moment_base = Rotate(u_conj, w_conj, a);
  const Eigen::Vector3d direction_base = Rotate(u_conj, w_conj, direction_world);

  const Eigen::Vector3d m = camera_R_base_ * moment_base + B_ * direction_base;
  const Eigen::Vector3d l = A_ * m;
  const double normal_squared = l.x() * l.x() + l.y() * l.y();
  if (!(normal_squared > 0)) return false;
  const double inverse_norm = 1 / std::sqrt(normal_squared);
  const double s0 = l.dot(p0_), s1 = l.dot(p1_);
  residuals[0] = s0 * inverse_norm;
  residuals[1] = s1 * inverse_norm;
  if (jacobians == nullptr) return true;

  // dr/dl: p^T / n - s l_xy^T / n^3.
  const double inverse_norm3 = inverse_norm * inverse_norm * inverse_norm;
  Eigen::Matrix<double, 2, 3> dr_dl;
  dr_dl.row(0) = p0_.transpose() * inverse_norm;
  dr_dl.row(1) = p1_.transpose() * inverse_norm;
  dr_dl(0, 0) -= s0 * l.x() * inverse_norm3;
  dr_dl(0, 1) -= s0 * l.y() * inverse_norm3;
  dr_dl(1, 0) -= s1 * l.x() * inverse_norm3;
  dr_dl(1, 1) -= s1 * l.y() * inverse_norm3;
  const Eigen::Matrix<double, 2, 3> G = dr_dl * A_;              // d r / d m_c
  const Eigen::Matrix<double, 2, 3> G_mb = G * camera_R_base_;   // d r / d m_b
  const Eigen::Matrix<double, 2, 3> G_db = G * B_;               // d r / d d_b
  // df/dv of the conjugate rotation (for a unit quaternion, base_R_world).
  const Eigen::Matrix3d Su = Skew(u_conj);
  const Eigen::Matrix3d M = Eigen::Matrix3d::Identity() + 2 * w_conj * Su + 2 * Su * Su;
  const Eigen::Matrix<double, 2, 3> G_a = G_mb * M;  // d r / d a

  if (jacobians[0] != nullptr) {
    Eigen::Matrix<double, 3, 4> dmb_dq = RotationDerivative(u_conj, w_conj, a);
    Eigen::Matrix<double, 3, 4> ddb_dq = RotationDerivative(u_conj, w_conj, direction_world);
    // d/du of f at -u is -df/du'.
    dmb_dq.leftCols<3>() *= -1;
    ddb_dq.leftCols<3>() *= -1;
    Eigen::Map<Eigen::Matrix<double, 2, 4, Eigen::RowMajor>> J(jacobians[0]);
    J = G_mb * dmb_dq + G_db * ddb_dq;
  }
  if (jacobians[1] != nullptr) {
    // a = m_w + d_w x t: da/dt = [d_w]x.
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> J(jacobians[1]);
    J = G_a * Skew(direction_world);
  }
  if (jacobians[2] != nullptr) {
    // d r / d m_w = G_a; d r / d d_w = G_a (-[t]x) + G_db M.
    const Eigen::Matrix<double, 2, 3> G_dw = -G_a * Skew(t) + G_db * M;
    // Derivatives of u1 and u2 by [x y z w].
    Eigen::Matrix<double, 3, 4> du1, du2;
    du1 << 0, -4 * y, -4 * z, 0,  //
        2 * y, 2 * x, 2 * w, 2 * z,  //
        2 * z, -2 * w, 2 * x, -2 * y;
    du2 << 2 * y, 2 * x, -2 * w, -2 * z,  //
        -4 * x, 0, -4 * z, 0,  //
        2 * w, 2 * z, 2 * y, 2 * x;
    Eigen::Map<Eigen::Matrix<double, 2, 6, Eigen::RowMajor>> J(jacobians[2]);
    J.leftCols<4>() = line[4] * G_a * du1 + line[5] * G_dw * du2;
    J.col(4) = G_a * u1;
    J.col(5) = G_dw * u2;
  }
  return true;
}

namespace {

void CheckOdometrySigmas(const Pose3& motion, double rotation_sigma_rad, double along_sigma_m,
                         double across_sigma_m) {
  CHECK_GT(rotation_sigma_rad, 0);
  CHECK_GT(along_sigma_m, 0);
  CHECK_GT(across_sigma_m, 0);
  // A step of zero length has no direction to be across from.
  if (!(motion.translation.norm() > 0)) CHECK_EQ(along_sigma_m, across_sigma_m);
}

}  // namespace

OdometryStepSigmas OdometryStepSigmasFor(double distance_m, const OdometryNoise& noise,
                                         const BundleAdjustmentOptions& options) {
  const double d = std::max(distance_m, options.odometry_min_distance_m);
  OdometryStepSigmas sigmas;
  sigmas.along_m = noise.translation_sigma * d;
  sigmas.across_m = noise.rotation_sigma * d;
  // Below the floor the measured direction is mostly slip: no direction is known better.
  if (distance_m < options.odometry_min_distance_m) {
    sigmas.along_m = sigmas.across_m = std::max(sigmas.along_m, sigmas.across_m);
  }
  return sigmas;
}

ceres::CostFunction* OdometryPriorCost::Create(const Pose3& base_i_T_base_j_odometry, double rotation_sigma_rad,
                                               double along_sigma_m, double across_sigma_m) {
  CheckOdometrySigmas(base_i_T_base_j_odometry, rotation_sigma_rad, along_sigma_m, across_sigma_m);
  return new ceres::AutoDiffCostFunction<OdometryPriorCost, 6, 4, 3, 4, 3, 1, 3>(
      new OdometryPriorCost(base_i_T_base_j_odometry, rotation_sigma_rad, along_sigma_m, across_sigma_m));
}

ceres::CostFunction* OdometryRotationBiasPriorCost::Create(double sigma_rad) {
  CHECK_GT(sigma_rad, 0);
  return new ceres::AutoDiffCostFunction<OdometryRotationBiasPriorCost, 3, 3>(
      new OdometryRotationBiasPriorCost(sigma_rad));
}

ceres::CostFunction* FloorPointCost::Create(double sigma_m) {
  CHECK_GT(sigma_m, 0);
  return new ceres::AutoDiffCostFunction<FloorPointCost, 1, 3>(new FloorPointCost(sigma_m));
}

ceres::CostFunction* FloorLineCost::Create(const Eigen::Vector3d& anchor0, const Eigen::Vector3d& anchor1,
                                           double sigma_m) {
  CHECK_GT(sigma_m, 0);
  return new ceres::AutoDiffCostFunction<FloorLineCost, 2, 6>(new FloorLineCost(anchor0, anchor1, sigma_m));
}

ceres::CostFunction* BaseOnFloorCost::Create(double sigma_m, double tilt_sigma_rad) {
  CHECK_GT(sigma_m, 0);
  CHECK_GT(tilt_sigma_rad, 0);
  return new ceres::AutoDiffCostFunction<BaseOnFloorCost, 3, 4, 3>(new BaseOnFloorCost(sigma_m, tilt_sigma_rad));
}

ceres::CostFunction* OdometryScalePriorCost::Create(double sigma) {
  CHECK_GT(sigma, 0);
  return new ceres::AutoDiffCostFunction<OdometryScalePriorCost, 1, 1>(new OdometryScalePriorCost(sigma));
}

}  // namespace sfm
