#include "backend/metrics/alignment.h"

#include <glog/logging.h>

#include <Eigen/SVD>

namespace sfm {
namespace {

// The second singular value of the cross-covariance, relative to the first, below which the points
// count as collinear. Exactly collinear points leave it at rounding level (~1e-16); 1e-12 still
// lets through sets whose spread across the line is a millionth of their spread along it, where
// the rotation about the line is ill-conditioned but still the least-squares answer.
constexpr double kCollinearRatio = 1e-12;

}  // namespace

Pose3 AlignSE3(const std::vector<Eigen::Vector3d>& estimated, const std::vector<Eigen::Vector3d>& truth,
               bool* rotation_determined) {
  CHECK_EQ(estimated.size(), truth.size()) << "AlignSE3 needs corresponding points";
  if (rotation_determined != nullptr) *rotation_determined = false;
  const size_t n = estimated.size();
  if (n == 0) return Pose3::Identity();

  Eigen::Vector3d mean_estimated = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_truth = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    mean_estimated += estimated[i];
    mean_truth += truth[i];
  }
  mean_estimated /= static_cast<double>(n);
  mean_truth /= static_cast<double>(n);

  // Cross-covariance Sigma = 1/n sum (truth_i - mu_t)(estimated_i - mu_e)^T (Umeyama eq. 38).
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    sigma += (truth[i] - mean_truth) * (estimated[i] - mean_estimated).transpose();
  }
  sigma /= static_cast<double>(n);

  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& singular = svd.singularValues();  // decreasing
  if (n < 3 || !(singular(1) > kCollinearRatio * singular(0))) {
    return Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(mean_truth - mean_estimated));
  }

  // With rank(Sigma) >= 2 the rotation is unique; S flips the weakest axis when U V^T would be a
  // reflection (Umeyama eq. 39, 40 and, for rank 2, 43); t is eq. 41 with scale 1.
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2, 2) = -1;
  const Eigen::Matrix3d R = svd.matrixU() * S * svd.matrixV().transpose();
  if (rotation_determined != nullptr) *rotation_determined = true;
  return Pose3(R, Eigen::Vector3d(mean_truth - R * mean_estimated));
}

}  // namespace sfm
