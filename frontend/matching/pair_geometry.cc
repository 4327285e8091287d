#include "frontend/matching/pair_geometry.h"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <glog/logging.h>

namespace sfm {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Eigen::Matrix3d Cross(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d ExpRotation(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle == 0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

Eigen::Vector3d LogRotation(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd angle_axis(R);
  return angle_axis.angle() * angle_axis.axis();
}

// The perturbation of `perturbed` relative to `pose` as (omega, dt): perturbed = (Exp(omega) R, t + dt).
Eigen::Matrix<double, 6, 1> Difference(const Pose3& perturbed, const Pose3& pose) {
  Eigen::Matrix<double, 6, 1> xi;
  xi.head<3>() = LogRotation(perturbed.RotationMatrix() * pose.RotationMatrix().transpose());
  xi.tail<3>() = perturbed.translation - pose.translation;
  return xi;
}

Pose3 Perturb(const Pose3& pose, const Eigen::Matrix<double, 6, 1>& xi) {
  return Pose3(Eigen::Matrix3d(ExpRotation(xi.head<3>()) * pose.RotationMatrix()), pose.translation + xi.tail<3>());
}

}  // namespace

// (Exp(w) R, t + dt)^-1 = (R^T Exp(-w), -R^T Exp(-w) (t + dt)) = (Exp(-R^T w) R^T,
// -R^T (t + dt + [t]x w)) to first order: w' = -R^T w, dt' = -R^T [t]x w - R^T dt.
PairGeometry InversePairGeometry(const PairGeometry& geometry) {
  const Eigen::Matrix3d R = geometry.camera2_T_camera1.RotationMatrix();
  const Eigen::Vector3d& t = geometry.camera2_T_camera1.translation;
  Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Zero();
  J.topLeftCorner<3, 3>() = -R.transpose();
  J.bottomLeftCorner<3, 3>() = -R.transpose() * Cross(t);
  J.bottomRightCorner<3, 3>() = -R.transpose();
  PairGeometry inverse;
  inverse.K = geometry.K;
  inverse.camera2_T_camera1 = geometry.camera2_T_camera1.Inverse();
  inverse.covariance = J * geometry.covariance * J.transpose();
  return inverse;
}

Eigen::Matrix3d PairGeometry::Fundamental() const {
  const Eigen::Matrix3d K_inverse = K.inverse();
  return K_inverse.transpose() * Cross(camera2_T_camera1.translation) * camera2_T_camera1.RotationMatrix() *
         K_inverse;
}

void PairGeometry::FundamentalDeviations(Eigen::Matrix3d G[6]) const {
  const Eigen::Matrix3d K_inverse = K.inverse();
  const Eigen::Matrix3d R = camera2_T_camera1.RotationMatrix();
  const Eigen::Matrix3d t_cross = Cross(camera2_T_camera1.translation);
  // d/d omega_j of [t]x Exp(omega) R = [t]x [e_j]x R; d/d t_j of [t + dt]x R = [e_j]x R.
  Eigen::Matrix3d derivative[6];
  for (int j = 0; j < 3; ++j) {
    const Eigen::Matrix3d e_cross = Cross(Eigen::Vector3d::Unit(j));
    derivative[j] = K_inverse.transpose() * t_cross * e_cross * R * K_inverse;
    derivative[3 + j] = K_inverse.transpose() * e_cross * R * K_inverse;
  }
  // covariance = V diag(l) V^T: z_k = V^T xi / sqrt(l_k) are independent standard normal.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(covariance);
  const Eigen::Matrix<double, 6, 6>& V = solver.eigenvectors();
  for (int k = 0; k < 6; ++k) {
    const double scale = std::sqrt(std::max(0.0, solver.eigenvalues()(k)));
    G[k].setZero();
    for (int j = 0; j < 6; ++j) G[k] += derivative[j] * (V(j, k) * scale);
  }
}

PairGeometry PairGeometryFromOdometry(const Eigen::Matrix3d& K, const Pose3& base_T_camera,
                                      const Pose3& world_T_base1, const Pose3& world_T_base2,
                                      double translation_sigma, double rotation_sigma, int frames_apart) {
  CHECK_GE(frames_apart, 1);
  CHECK_GE(translation_sigma, 0);
  CHECK_GE(rotation_sigma, 0);
  const Pose3 base1_T_base2 = world_T_base1.Inverse() * world_T_base2;
  auto camera2_T_camera1 = [&base_T_camera](const Pose3& base1_T_base2_noisy) {
    return (base_T_camera.Inverse() * base1_T_base2_noisy * base_T_camera).Inverse();
  };
  PairGeometry geometry;
  geometry.K = K;
  geometry.camera2_T_camera1 = camera2_T_camera1(base1_T_base2);
  // Numerical Jacobian of the camera perturbation with respect to the base increment's.
  Eigen::Matrix<double, 6, 6> J;
  constexpr double kStep = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> xi = Eigen::Matrix<double, 6, 1>::Zero();
    xi(k) = kStep;
    const Eigen::Matrix<double, 6, 1> plus =
        Difference(camera2_T_camera1(Perturb(base1_T_base2, xi)), geometry.camera2_T_camera1);
    const Eigen::Matrix<double, 6, 1> minus =
        Difference(camera2_T_camera1(Perturb(base1_T_base2, -xi)), geometry.camera2_T_camera1);
    J.col(k) = (plus - minus) / (2 * kStep);
  }
  // Wheel odometry: the distance error (wheel radius, slip) lies along the step; the step's
  // direction is as uncertain as the heading over the interval.
  const double rotation_variance = frames_apart * rotation_sigma * rotation_sigma;
  const Eigen::Vector3d& step = base1_T_base2.translation;
  const double distance_squared = step.squaredNorm();
  Eigen::Matrix3d translation_covariance = rotation_variance * distance_squared * Eigen::Matrix3d::Identity();
  if (distance_squared > 0) {
    translation_covariance +=
        (translation_sigma * translation_sigma - rotation_variance) * step * step.transpose();
  }
  Eigen::Matrix<double, 6, 6> base_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  base_covariance.topLeftCorner<3, 3>() = rotation_variance * Eigen::Matrix3d::Identity();
  base_covariance.bottomRightCorner<3, 3>() = translation_covariance;
  geometry.covariance = J * base_covariance * J.transpose();
  return geometry;
}

EpipolarDistanceSigmas EpipolarSigmas(const PairGeometry& geometry, const Eigen::Vector2d& x1,
                                      const Eigen::Vector2d& x2) {
  Eigen::Matrix3d G[6];
  geometry.FundamentalDeviations(G);
  const Eigen::Matrix3d F = geometry.Fundamental();
  const Eigen::Vector3d h1 = x1.homogeneous();
  const Eigen::Vector3d h2 = x2.homogeneous();
  double variance = 0;
  for (const Eigen::Matrix3d& g : G) {
    const double e = h2.dot(g * h1);
    variance += e * e;
  }
  const double sigma = std::sqrt(variance);
  const double norm2 = (F * h1).head<2>().norm();
  const double norm1 = (F.transpose() * h2).head<2>().norm();
  EpipolarDistanceSigmas sigmas;
  sigmas.in_image2 = norm2 > 0 ? sigma / norm2 : kInfinity;
  sigmas.in_image1 = norm1 > 0 ? sigma / norm1 : kInfinity;
  return sigmas;
}

ParallaxFrame ParallaxFrameOf(const PairGeometry& geometry, const Eigen::Vector2d& x1) {
  ParallaxFrame frame;
  const Eigen::Matrix3d& K = geometry.K;
  const Eigen::Vector3d& t = geometry.camera2_T_camera1.translation;
  // The ray of x1 in camera 2's axes; its point at infinity must be in front of camera 2.
  // K is upper triangular: a back substitution, not an inverse (this runs for every junction).
  const Eigen::Vector3d X =
      geometry.camera2_T_camera1.RotationMatrix() * K.triangularView<Eigen::Upper>().solve(x1.homogeneous());
  if (!(X.z() > 1e-9 * X.norm())) return frame;
  const Eigen::Vector3d p = K * X;
  frame.v = p.head<2>() / p.z();
  // Image of X/z1 + t as 1/z1 grows from 0, in normalised coordinates, then pixels.
  const Eigen::Vector2d m = X.head<2>() / X.z();
  const Eigen::Vector2d w_normalised = t.head<2>() - m * t.z();
  const Eigen::Vector2d w = K.topLeftCorner<2, 2>() * w_normalised;
  if (!(w.norm() > 1e-12 * (std::abs(K(0, 0)) + std::abs(K(1, 1))) * t.norm())) return frame;
  frame.direction = w.normalized();
  frame.scale = w.norm();
  frame.ray_z = X.z();
  // v moves with the rotation: X -> X + omega x X = X - [X]x omega.
  Eigen::Matrix<double, 2, 3> dv_dp;
  dv_dp << 1 / p.z(), 0, -p.x() / (p.z() * p.z()), 0, 1 / p.z(), -p.y() / (p.z() * p.z());
  const Eigen::RowVector3d j = frame.direction.transpose() * dv_dp * K * (-Cross(X));
  frame.sigma = std::sqrt(std::max(0.0, double(j * geometry.covariance.topLeftCorner<3, 3>() * j.transpose())));
  frame.tested = true;
  return frame;
}

Parallax ParallaxInImage2(const PairGeometry& geometry, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2) {
  const ParallaxFrame frame = ParallaxFrameOf(geometry, x1);
  Parallax result;
  if (!frame.tested) {
    result.sigma = kInfinity;
    return result;
  }
  result.parallax = (x2 - frame.v).dot(frame.direction);
  result.sigma = frame.sigma;
  return result;
}

bool PassesCheirality(const PairGeometry& geometry, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                      double num_sigmas, double location_sigma_px) {
  const Parallax forward = ParallaxInImage2(geometry, x1, x2);
  if (std::isfinite(forward.sigma) &&
      forward.parallax < -EpipolarBand(forward.sigma, location_sigma_px, num_sigmas)) {
    return false;
  }
  const Parallax backward = ParallaxInImage2(InversePairGeometry(geometry), x2, x1);
  return !(std::isfinite(backward.sigma) &&
           backward.parallax < -EpipolarBand(backward.sigma, location_sigma_px, num_sigmas));
}

}  // namespace sfm
