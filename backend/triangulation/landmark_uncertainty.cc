#include "backend/triangulation/landmark_uncertainty.h"

#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace sfm {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// d pixel / d world point at `p_camera` (camera frame, z > 0) for the camera with rotation R
// (camera_R_world).
Eigen::Matrix<double, 2, 3> PixelJacobian(const Eigen::Matrix3d& K, const Eigen::Matrix3d& camera_R_world,
                                          const Eigen::Vector3d& p) {
  Eigen::Matrix<double, 2, 3> d_normalised;
  d_normalised << 1 / p.z(), 0, -p.x() / (p.z() * p.z()), 0, 1 / p.z(), -p.y() / (p.z() * p.z());
  return K.topLeftCorner<2, 2>() * d_normalised * camera_R_world;
}

// The standard normal p-quantile (Acklam's rational approximation, relative error < 1.2e-9).
double NormalQuantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01,  -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double low = 0.02425;
  if (p < low) {
    const double q = std::sqrt(-2 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  if (p > 1 - low) return -NormalQuantile(1 - p);
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

}  // namespace

double PointPositionSigma(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const Eigen::Vector3d& point, double sigma_px) {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  for (const Pose3& camera : world_T_camera) {
    const Pose3 camera_T_world = camera.Inverse();
    const Eigen::Vector3d p = camera_T_world * point;
    if (!(p.z() > 0)) return kInfinity;
    const Eigen::Matrix<double, 2, 3> J = PixelJacobian(K, camera_T_world.RotationMatrix(), p);
    information += J.transpose() * J;
  }
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(information).eigenvalues().minCoeff();
  // Relative to the largest: a rank-deficient information matrix is not inverted.
  if (!(smallest > 1e-12 * information.trace())) return kInfinity;
  return sigma_px / std::sqrt(smallest);
}

double LinePositionSigma(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                         const Eigen::Vector3d& x, const Eigen::Vector3d& direction, double sigma_px) {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  for (const LineSegmentView& view : views) {
    const Pose3 camera_T_world = view.world_T_camera.Inverse();
    const Eigen::Vector3d p = camera_T_world * x;
    if (!(p.z() > 0)) return kInfinity;
    const Eigen::Vector2d pixel = (K * p).hnormalized();
    const Eigen::Vector2d along = view.p1 - view.p0;
    CHECK_GT(along.squaredNorm(), 0) << "a line view needs p0 != p1";
    const double t = (pixel - view.p0).dot(along) / along.squaredNorm();
    const Eigen::Vector2d normal = Eigen::Vector2d(-along.y(), along.x()).normalized();
    const Eigen::Vector3d g = PixelJacobian(K, camera_T_world.RotationMatrix(), p).transpose() * normal;
    information += g * g.transpose() / ((1 - t) * (1 - t) + t * t);
  }
  const Eigen::Vector3d u = direction.normalized();
  const Eigen::Vector3d a = u.unitOrthogonal(), b = u.cross(a);
  Eigen::Matrix2d across;
  across << a.dot(information * a), a.dot(information * b), b.dot(information * a), b.dot(information * b);
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(across).eigenvalues().minCoeff();
  if (!(smallest > 1e-12 * across.trace())) return kInfinity;
  return sigma_px / std::sqrt(smallest);
}

double PointChiSquare(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                      const std::vector<Eigen::Vector2d>& pixels, const Eigen::Vector3d& point,
                      double sigma_px, int* degrees_of_freedom) {
  CHECK_EQ(world_T_camera.size(), pixels.size());
  *degrees_of_freedom = 2 * static_cast<int>(pixels.size()) - 3;
  double sum = 0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector3d p = world_T_camera[i].Inverse() * point;
    if (!(p.z() > 0)) return kInfinity;
    sum += ((K * p).hnormalized() - pixels[i]).squaredNorm();
  }
  return sum / (sigma_px * sigma_px);
}

double LineChiSquare(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                     const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double sigma_px,
                     int* degrees_of_freedom) {
  *degrees_of_freedom = 2 * static_cast<int>(views.size()) - 4;
  const Eigen::Matrix3d K_inverse_transpose = K.inverse().transpose();
  double sum = 0;
  for (const LineSegmentView& view : views) {
    const Pose3 camera_T_world = view.world_T_camera.Inverse();
    const Eigen::Vector3d l =
        K_inverse_transpose * (camera_T_world * point).cross(camera_T_world.rotation * direction);
    const double scale = l.head<2>().norm();
    if (!(scale > 0)) return kInfinity;
    const double e0 = l.dot(view.p0.homogeneous()) / scale, e1 = l.dot(view.p1.homogeneous()) / scale;
    sum += e0 * e0 + e1 * e1;
  }
  return sum / (sigma_px * sigma_px);
}

double ChiSquareQuantile(double p, int k) {
  CHECK(p > 0 && p < 1) << p;
  CHECK_GE(k, 1);
  const double h = 2.0 / (9.0 * k);
  const double cube_root = 1 - h + NormalQuantile(p) * std::sqrt(h);
  return k * cube_root * cube_root * cube_root;
}

}  // namespace sfm
