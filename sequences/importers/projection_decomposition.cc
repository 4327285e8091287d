#include "util/number_text.h"
#include "sequences/importers/projection_decomposition.h"

#include <cmath>

#include <Eigen/LU>
#include <Eigen/QR>

#include "sequences/importers/input_files.h"

namespace sfm {
namespace {

// |det M| below this times |M|^3 (Frobenius) is a singular left block: no finite camera centre.
constexpr double kRelativeDeterminantFloor = 1e-12;

}  // namespace

Status DecomposeProjection(const Eigen::Matrix<double, 3, 4>& P_in, ProjectionDecomposition* decomposition) {
  if (!P_in.allFinite()) return Status::Error("projection matrix has a non-finite entry");
  Eigen::Matrix3d M = P_in.leftCols<3>();
  const double determinant = M.determinant();
  const double norm = M.norm();
  if (!(std::abs(determinant) > kRelativeDeterminantFloor * norm * norm * norm)) {
    return Status::Error("projection matrix's left 3x3 block is singular (det " + ShortestNumberText(determinant) + ")");
  }
  // P is defined up to scale; with det M > 0, M = K R has det R = +1 once K's diagonal is positive.
  const Eigen::Matrix<double, 3, 4> P = determinant < 0 ? Eigen::Matrix<double, 3, 4>(-P_in) : P_in;
  M = P.leftCols<3>();

  // RQ from QR (H&Z A4.1.1): with J the exchange matrix, (J M)^T = Q U gives M = (J U^T J)(J Q^T),
  // an upper-triangular times an orthogonal matrix.
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  J(0, 2) = J(1, 1) = J(2, 0) = 1;
  const Eigen::HouseholderQR<Eigen::Matrix3d> qr((J * M).transpose());
  const Eigen::Matrix3d Q = qr.householderQ();
  const Eigen::Matrix3d U = qr.matrixQR().triangularView<Eigen::Upper>();
  Eigen::Matrix3d K = J * U.transpose() * J;
  Eigen::Matrix3d R = J * Q.transpose();
  // K D D R with D = diag(sign K_ii) makes K's diagonal positive without changing the product.
  const Eigen::Vector3d signs(K(0, 0) < 0 ? -1 : 1, K(1, 1) < 0 ? -1 : 1, K(2, 2) < 0 ? -1 : 1);
  K = K * signs.asDiagonal();
  R = signs.asDiagonal() * R;

  const Eigen::Vector3d t = K.inverse() * P.col(3);  // P = K [R | t] before K is normalised
  decomposition->K = K / K(2, 2);
  decomposition->K(1, 0) = decomposition->K(2, 0) = decomposition->K(2, 1) = 0;
  decomposition->camera_T_world = Pose3(R, t);
  decomposition->centre = -R.transpose() * t;
  return Status::Ok();
}

}  // namespace sfm
