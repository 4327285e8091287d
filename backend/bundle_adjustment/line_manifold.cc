#include "backend/bundle_adjustment/line_manifold.h"

#include <glog/logging.h>

#include <cmath>

namespace sfm {
namespace {

using Quaternion = Eigen::Quaterniond;
using QuaternionMap = Eigen::Map<const Eigen::Quaterniond>;

// The unit quaternion of the rotation vector theta (angle |theta|, radians).
Quaternion ExpRotation(const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  // sin(angle / 2) / angle -> 1/2 as angle -> 0; below 1e-10 the series' next term is < 1e-21.
  const double scale = angle > 1e-10 ? std::sin(0.5 * angle) / angle : 0.5;
  return Quaternion(std::cos(0.5 * angle), scale * theta.x(), scale * theta.y(), scale * theta.z());
}

// The rotation vector of q with angle in [0, 2 pi]: q itself, not -q, is reproduced by ExpRotation.
Eigen::Vector3d LogRotation(const Quaternion& q) {
  const double s = q.vec().norm();
  if (s > 0) return (2 * std::atan2(s, q.w()) / s) * q.vec();
  // s = 0: q = +1 (no rotation) or q = -1 (a full turn, about any axis).
  return q.w() >= 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(2 * M_PI, 0, 0);
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

OrthonormalLine OrthonormalLineFromPointDirection(const Eigen::Vector3d& point,
                                                  const Eigen::Vector3d& direction) {
  CHECK_GT(direction.norm(), 0) << "a line needs a direction";
  const Eigen::Vector3d d = direction.normalized();
  const Eigen::Vector3d moment = point.cross(d);
  const double distance = moment.norm();  // of the line from the origin, as |d| = 1
  Eigen::Vector3d u1;
  if (distance > 1e-12) {
    u1 = moment / distance;
  } else {
    // Through the origin: any unit vector orthogonal to d; take the one from d's smallest axis.
    Eigen::Index axis;
    d.cwiseAbs().minCoeff(&axis);
    u1 = d.cross(Eigen::Vector3d::Unit(axis)).normalized();
  }
  Eigen::Matrix3d U;
  U.col(0) = u1;
  U.col(1) = d;
  U.col(2) = u1.cross(d);
  const Quaternion u(U);
  const double norm = std::hypot(distance, 1.0);
  return {u.x(), u.y(), u.z(), u.w(), distance / norm, 1.0 / norm};
}

void OrthonormalLineToPointDirection(const OrthonormalLine& line, Eigen::Vector3d* point,
                                     Eigen::Vector3d* direction) {
  CHECK_NE(line[5], 0) << "a line at infinity has no point";
  const Eigen::Matrix3d U = QuaternionMap(line.data()).normalized().toRotationMatrix();
  // (m, d) ~ (w1 u1, w2 u2); the closest point to the origin is d x m / |d|^2 = -(w1 / w2) u3.
  *direction = line[5] > 0 ? U.col(1) : Eigen::Vector3d(-U.col(1));
  *point = -(line[4] / line[5]) * U.col(2);
}

bool OrthonormalLineManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const Quaternion u =
      (QuaternionMap(x) * ExpRotation(Eigen::Vector3d(delta[0], delta[1], delta[2]))).normalized();
  const double c = std::cos(delta[3]), s = std::sin(delta[3]);
  // First column of W R(phi) for W = [w1 -w2; w2 w1].
  const Eigen::Vector2d w = Eigen::Vector2d(x[4] * c - x[5] * s, x[5] * c + x[4] * s).normalized();
  Eigen::Map<Eigen::Vector4d> u_out(x_plus_delta);
  u_out = u.coeffs();
  x_plus_delta[4] = w.x();
  x_plus_delta[5] = w.y();
  return true;
}

bool OrthonormalLineManifold::PlusJacobian(const double* x, double* jacobian) const {
  // u (+) theta = u * (1, theta / 2) to first order: the vector part moves by (w I + [v]x) theta / 2,
  // the scalar part by -v . theta / 2 (v, w: u's vector and scalar parts).
  const QuaternionMap u(x);
  Eigen::Map<Eigen::Matrix<double, 6, 4, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.block<3, 3>(0, 0) = 0.5 * (u.w() * Eigen::Matrix3d::Identity() + Skew(u.vec()));
  J.block<1, 3>(3, 0) = -0.5 * u.vec().transpose();
  J(4, 3) = -x[5];
  J(5, 3) = x[4];
  return true;
}

bool OrthonormalLineManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  const Eigen::Vector3d theta = LogRotation(QuaternionMap(x).conjugate() * QuaternionMap(y));
  y_minus_x[0] = theta.x();
  y_minus_x[1] = theta.y();
  y_minus_x[2] = theta.z();
  // The angle of W_x^T W_y.
  y_minus_x[3] = std::atan2(x[4] * y[5] - x[5] * y[4], x[4] * y[4] + x[5] * y[5]);
  return true;
}

bool OrthonormalLineManifold::MinusJacobian(const double* x, double* jacobian) const {
  // At y = x: theta = 2 vec(conj(u_x) * u_y) to first order, whose derivative in u_y is
  // [w I - [v]x, -v] (columns qx qy qz | qw); phi moves by (-w2, w1) . dw_y.
  const QuaternionMap u(x);
  Eigen::Map<Eigen::Matrix<double, 4, 6, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.block<3, 3>(0, 0) = 2 * (u.w() * Eigen::Matrix3d::Identity() - Skew(u.vec()));
  J.block<3, 1>(0, 3) = -2 * u.vec();
  J(3, 4) = -x[5];
  J(3, 5) = x[4];
  return true;
}

}  // namespace sfm
