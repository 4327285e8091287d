// The orthonormal representation of a 3D line (Bartoli & Sturm, "Structure-from-motion using
// lines: representation, triangulation and bundle adjustment", CVIU 100(3), 2005) as a 4-DOF
// ceres::Manifold.
//
// A line with Plücker coordinates (m, d) - moment m = p x d for any point p on it, direction d -
// is written (U, W) with U in SO(3) and W in SO(2):
//   U = [m/|m|, d/|d|, (m x d)/|m x d|],   W = [w1 -w2; w2 w1],  (w1, w2) = (|m|, |d|) / |(|m|, |d|)|
// so that (m, d) ~ (w1 u1, w2 u2). The ambient vector has 6 numbers:
//   [qx qy qz qw w1 w2]   U as a unit quaternion in Eigen's storage order, then W's first column.
// Tangent (4): [theta_x theta_y theta_z phi], the local update of B&S's bundle adjustment:
//   U <- U R(theta)   (theta a rotation vector, radians; R its rotation matrix)
//   W <- W R(phi)     (phi radians)
// For a line with unit direction, w1 / w2 is its distance from the world origin (metres).
#pragma once

#include <ceres/manifold.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

namespace sfm {

using OrthonormalLine = std::array<double, 6>;  // [qx qy qz qw w1 w2]

// The orthonormal representation of the line through `point` with direction `direction` (any
// length > 0). A line through the origin (m = 0) gets u1 = any unit vector orthogonal to d, w1 = 0.
OrthonormalLine OrthonormalLineFromPointDirection(const Eigen::Vector3d& point,
                                                  const Eigen::Vector3d& direction);

// The point of the line closest to the world origin and its unit direction. w2 must not be 0
// (a line at infinity), CHECKed.
void OrthonormalLineToPointDirection(const OrthonormalLine& line, Eigen::Vector3d* point,
                                     Eigen::Vector3d* direction);

// Plücker coordinates (m, d) = (w1 u1, w2 u2) of the orthonormal parameters, up to the common
// scale 1 / |(|m|, |d|)| (B&S: L ~ (w1 u1, w2 u2)); templated for ceres::Jet.
template <typename T>
void PluckerFromOrthonormal(const T* line, Eigen::Matrix<T, 3, 1>* moment,
                            Eigen::Matrix<T, 3, 1>* direction) {
  const Eigen::Map<const Eigen::Quaternion<T>> u(line);
  const Eigen::Matrix<T, 3, 3> U = u.toRotationMatrix();
  *moment = line[4] * U.col(0);
  *direction = line[5] * U.col(1);
}

class OrthonormalLineManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 6; }
  int TangentSize() const override { return 4; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  // Row-major 6 x 4: d Plus(x, delta) / d delta at delta = 0.
  bool PlusJacobian(const double* x, double* jacobian) const override;
  // The delta with Plus(x, delta) = y: theta of angle in [0, 2 pi] (no quaternion sign flip, so
  // that Plus(x, Minus(y, x)) = y holds for the stored numbers), phi in (-pi, pi].
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  // Row-major 4 x 6: d Minus(y, x) / d y at y = x.
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

}  // namespace sfm
