#include "geometry/alignment.h"

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

namespace {

// The least-squares rotation and the terms the scale needs: Umeyama eq. 38-43.
struct Umeyama {
  Eigen::Vector3d mean_estimated = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_truth = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  bool rotation_determined = false;
  double trace_d_s = 0;           // tr(D S): the numerator of the scale (eq. 42)
  double variance_estimated = 0;  // sigma_e^2: the denominator
};

Umeyama SolveUmeyama(const std::vector<Eigen::Vector3d>& estimated,
                     const std::vector<Eigen::Vector3d>& truth) {
  Umeyama result;
  const size_t n = estimated.size();
  if (n == 0) return result;
  for (size_t i = 0; i < n; ++i) {
    result.mean_estimated += estimated[i];
    result.mean_truth += truth[i];
  }
  result.mean_estimated /= static_cast<double>(n);
  result.mean_truth /= static_cast<double>(n);

  // Cross-covariance Sigma = 1/n sum (truth_i - mu_t)(estimated_i - mu_e)^T (Umeyama eq. 38).
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d centred = estimated[i] - result.mean_estimated;
    sigma += (truth[i] - result.mean_truth) * centred.transpose();
    result.variance_estimated += centred.squaredNorm();
  }
  sigma /= static_cast<double>(n);
  result.variance_estimated /= static_cast<double>(n);

  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& singular = svd.singularValues();  // decreasing
  if (n < 3 || !(singular(1) > kCollinearRatio * singular(0))) {
    // Rotation undetermined: identity, and tr(R^T Sigma) = tr(Sigma) is what the scale sees.
    result.trace_d_s = sigma.trace();
    return result;
  }
  // With rank(Sigma) >= 2 the rotation is unique; S flips the weakest axis when U V^T would be a
  // reflection (Umeyama eq. 39, 40 and, for rank 2, 43).
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2, 2) = -1;
  result.rotation = svd.matrixU() * S * svd.matrixV().transpose();
  result.rotation_determined = true;
  result.trace_d_s = singular.dot(S.diagonal());
  return result;
}

}  // namespace

Pose3 AlignSE3(const std::vector<Eigen::Vector3d>& estimated, const std::vector<Eigen::Vector3d>& truth,
               bool* rotation_determined) {
  CHECK_EQ(estimated.size(), truth.size()) << "AlignSE3 needs corresponding points";
  const Umeyama u = SolveUmeyama(estimated, truth);
  if (rotation_determined != nullptr) *rotation_determined = u.rotation_determined;
  // Eq. 41 with scale 1.
  return Pose3(u.rotation, Eigen::Vector3d(u.mean_truth - u.rotation * u.mean_estimated));
}

Similarity3 AlignSim3(const std::vector<Eigen::Vector3d>& estimated,
                      const std::vector<Eigen::Vector3d>& truth, bool* rotation_determined) {
  CHECK_EQ(estimated.size(), truth.size()) << "AlignSim3 needs corresponding points";
  const Umeyama u = SolveUmeyama(estimated, truth);
  if (rotation_determined != nullptr) *rotation_determined = u.rotation_determined;
  Similarity3 similarity;
  // Eq. 42; coincident estimated points leave the scale undetermined: keep 1.
  if (u.variance_estimated > 0) similarity.scale = u.trace_d_s / u.variance_estimated;
  // Eq. 41.
  similarity.rigid =
      Pose3(u.rotation, Eigen::Vector3d(u.mean_truth - similarity.scale * u.rotation * u.mean_estimated));
  return similarity;
}

}  // namespace sfm
