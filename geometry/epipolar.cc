#include "geometry/epipolar.h"

#include <cmath>
#include <limits>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace sfm {
namespace {

Eigen::Matrix3d CrossMatrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

Eigen::Matrix3d FundamentalFromPoses(const Eigen::Matrix3d& K, const Pose3& world_T_camera1,
                                     const Pose3& world_T_camera2) {
  // With p2 = R p1 + t (camera2_T_camera1), the essential matrix is E = [t]x R (H&Z eq. 9.12).
  const Pose3 camera2_T_camera1 = world_T_camera2.Inverse() * world_T_camera1;
  const Eigen::Matrix3d E = CrossMatrix(camera2_T_camera1.translation) * camera2_T_camera1.RotationMatrix();
  const Eigen::Matrix3d K_inverse = K.inverse();
  return K_inverse.transpose() * E * K_inverse;
}

Eigen::Matrix3d FundamentalFromOdometry(const Eigen::Matrix3d& K, const Pose3& base_T_camera,
                                        const Pose3& world_T_base1, const Pose3& world_T_base2) {
  return FundamentalFromPoses(K, world_T_base1 * base_T_camera, world_T_base2 * base_T_camera);
}

Eigen::Matrix3d FundamentalFromProjections(const Eigen::Matrix<double, 3, 4>& P1,
                                           const Eigen::Matrix<double, 3, 4>& P2) {
  // H&Z eq. 9.1: C1 is the right null vector of P1 (camera 1's centre), e2 = P2 C1 its image in
  // camera 2, and P1^+ = P1^T (P1 P1^T)^-1 the right pseudo-inverse.
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 4>> svd(P1, Eigen::ComputeFullV);
  const Eigen::Vector4d C1 = svd.matrixV().col(3);
  const Eigen::Matrix<double, 4, 3> P1_pseudo_inverse = P1.transpose() * (P1 * P1.transpose()).inverse();
  return CrossMatrix(P2 * C1) * P2 * P1_pseudo_inverse;
}

Eigen::Vector3d EpipolarLineInImage2(const Eigen::Matrix3d& F, const Eigen::Vector2d& p1) {
  return F * p1.homogeneous();
}

Eigen::Vector3d EpipolarLineInImage1(const Eigen::Matrix3d& F, const Eigen::Vector2d& p2) {
  return F.transpose() * p2.homogeneous();
}

double PointLineDistance(const Eigen::Vector3d& line, const Eigen::Vector2d& p) {
  const double normal_norm = line.head<2>().norm();
  if (normal_norm == 0) return std::numeric_limits<double>::infinity();
  return std::abs(line.dot(p.homogeneous())) / normal_norm;
}

double SymmetricEpipolarDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& p1,
                                 const Eigen::Vector2d& p2) {
  return 0.5 * (PointLineDistance(EpipolarLineInImage2(F, p1), p2) +
                PointLineDistance(EpipolarLineInImage1(F, p2), p1));
}

}  // namespace sfm
