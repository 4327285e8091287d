#include "backend/initialization/visual_constraints.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "util/parallel.h"

namespace sfm {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

// Pseudo-inverse of a symmetric PSD matrix: directions with variance below 1e-12 of the largest
// carry infinite information in principle; they are held (no information is added along them).
Matrix6 PseudoInverse(const Matrix6& covariance) {
  const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(0.5 * (covariance + covariance.transpose()));
  const double largest = eigen.eigenvalues().maxCoeff();
  Eigen::Matrix<double, 6, 1> inverse = Eigen::Matrix<double, 6, 1>::Zero();
  for (int k = 0; k < 6; ++k) {
    if (largest > 0 && eigen.eigenvalues()(k) > 1e-12 * largest) inverse(k) = 1 / eigen.eigenvalues()(k);
  }
  return eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
}

// RelativePoseFromMatches: how much wider the second fit's prior is than the first's posterior,
// per sigma. The prior's pull on a direction the matches determine is then about 1/100 of theirs.
constexpr double kPriorWidening = 10;
// RANSAC's confidence of having drawn one all-inlier sample.
constexpr double kEssentialConfidence = 0.999;

// The MAP covariance widened by kPriorWidening in every sigma but the translation's length (along
// `translation`), which the matches cannot measure: there the odometry's sigma stays, or the fit
// could shrink the translation through zero to its mirror image, which fits the matches as well.
Matrix6 WidenedPrior(const Matrix6& covariance, const Eigen::Vector3d& translation) {
  const double widening = kPriorWidening * kPriorWidening;
  Matrix6 wide = Matrix6::Zero();
  wide.topLeftCorner<3, 3>() = widening * covariance.topLeftCorner<3, 3>();
  const Eigen::Matrix3d along = translation.norm() > 0
                                    ? Eigen::Matrix3d(translation.normalized() * translation.normalized().transpose())
                                    : Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - along;
  const Eigen::Matrix3d translation_covariance = covariance.bottomRightCorner<3, 3>();
  wide.bottomRightCorner<3, 3>() = widening * across * translation_covariance * across +
                                   along * translation_covariance * along;
  return wide;
}

}  // namespace

PairRefinement RelativePoseFromMatches(const PairRefinement& refinement, const std::vector<Eigen::Vector2d>& x1,
                                       const std::vector<Eigen::Vector2d>& x2,
                                       const PairRefinementSettings& settings, PairGeometry* prior_used,
                                       bool repeated_pattern) {
  const PairGeometry& map = refinement.geometry;
  PairGeometry wide = map;
  // The inliers and the start from the essential matrix (OpenCV's RANSAC, Nister's five-point
  // solver), at the refinement's gate on the location noise; the start's translation keeps the MAP
  // pose's length, which the matches do not measure.
  std::vector<cv::Point2d> points1, points2;
  for (size_t i = 0; i < x1.size(); ++i) {
    points1.emplace_back(x1[i].x(), x1[i].y());
    points2.emplace_back(x2[i].x(), x2[i].y());
  }
  cv::Mat K;
  cv::eigen2cv(map.K, K);
  std::vector<Eigen::Vector2d> inliers1, inliers2;
  if (static_cast<int>(x1.size()) >= std::max(settings.min_inliers, 5)) {
    cv::Mat mask;
    const cv::Mat E = cv::findEssentialMat(points1, points2, K, cv::RANSAC, kEssentialConfidence,
                                           settings.gate_sigmas * settings.location_sigma_px, mask);
    cv::Mat R, t;
    if (E.rows == 3 && E.cols == 3 && cv::recoverPose(E, points1, points2, K, R, t, mask) >= settings.min_inliers) {
      Eigen::Matrix3d rotation;
      Eigen::Vector3d direction;
      cv::cv2eigen(R, rotation);
      cv::cv2eigen(t, direction);
      // The sign of the direction that recoverPose's cheirality vote chose can flip when wrong
      // matches vote; the odometry's prior knows which way the robot went.
      if (direction.dot(map.camera2_T_camera1.translation) < 0) direction = -direction;
      const Pose3 start(Eigen::Quaterniond(rotation).normalized(),
                        direction.normalized() * map.camera2_T_camera1.translation.norm());
      // On a repeated pattern, an essential matrix whose epipolar lines run along the repetition
      // explains the right and the shifted copies at once. Such a start lies beyond the odometry's
      // own uncertainty (the MAP pose's prior): the MAP pose and its inliers are kept.
      int rank = 0;
      const double distance_squared =
          repeated_pattern ? PriorDistanceSquared(refinement.prior, start, &rank) : 0.0;
      if (rank == 0 || distance_squared <= ChiSquare99(rank)) {
        wide.camera2_T_camera1 = start;
        for (size_t i = 0; i < x1.size(); ++i) {
          if (mask.at<unsigned char>(static_cast<int>(i)) == 0) continue;
          inliers1.push_back(x1[i]);
          inliers2.push_back(x2[i]);
        }
      }
    }
  }
  if (inliers1.empty()) {
    // No essential matrix, or one beyond the MAP pose: the inliers of the MAP pose.
    const Eigen::Matrix3d F = map.Fundamental();
    for (size_t i = 0; i < x1.size(); ++i) {
      if (std::abs(SampsonDistance(F, x1[i], x2[i])) <= settings.gate_sigmas * settings.location_sigma_px) {
        inliers1.push_back(x1[i]);
        inliers2.push_back(x2[i]);
      }
    }
  }
  wide.covariance = WidenedPrior(map.covariance, wide.camera2_T_camera1.translation);
  if (prior_used != nullptr) *prior_used = wide;
  return RefinePairGeometry(wide, inliers1, inliers2, settings);
}

Matrix6 InformationFromMatches(const PairGeometry& prior, const PairGeometry& posterior) {
  const Matrix6 difference = PseudoInverse(posterior.covariance) - PseudoInverse(prior.covariance);
  const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(0.5 * (difference + difference.transpose()));
  const Eigen::Matrix<double, 6, 1> values = eigen.eigenvalues().cwiseMax(0);
  return eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
}

std::vector<RelativePoseConstraint> VisualConstraints(const std::vector<FramePairMatches>& matches,
                                                      const std::vector<Junctions>& frames,
                                                      const std::vector<MatchingDiagnostics>& diagnostics,
                                                      const PairRefinementSettings& settings,
                                                      VisualConstraintCounts* counts) {
  // Each pair's pose alone, in parallel (util/parallel.h), into its own slot; then counted in the
  // pairs' order.
  enum class Outcome { kConstraint, kTooFewMatches, kTooFewInliers, kInconsistentWithPrior, kNoInformation };
  const int n = static_cast<int>(matches.size());
  std::vector<Outcome> outcomes(n, Outcome::kConstraint);
  std::vector<RelativePoseConstraint> per_pair(n);
  ParallelFor(n, [&](int p) {
    const PairRefinement& refinement = diagnostics[p].refinement;
    switch (refinement.outcome) {
      case PairRefinement::Outcome::kRefined:
        break;
      case PairRefinement::Outcome::kTooFewInliers:
        outcomes[p] = Outcome::kTooFewInliers;
        return;
      case PairRefinement::Outcome::kInconsistentWithPrior:
        outcomes[p] = Outcome::kInconsistentWithPrior;
        return;
      case PairRefinement::Outcome::kTooFewMatches:
      case PairRefinement::Outcome::kNoPriorUncertainty:
        outcomes[p] = Outcome::kTooFewMatches;
        return;
    }
    const FramePairMatches& pair = matches[p];
    std::vector<Eigen::Vector2d> x1, x2;
    for (const JunctionMatch& match : pair.matches) {
      x1.push_back(frames[pair.frame_a][match.index_a].location);
      x2.push_back(frames[pair.frame_b][match.index_b].location);
    }
    PairGeometry fit_prior;
    const PairRefinement images =
        RelativePoseFromMatches(refinement, x1, x2, settings, &fit_prior, diagnostics[p].recentred);
    if (!images.Refined()) {
      outcomes[p] = Outcome::kTooFewInliers;
      return;
    }
    RelativePoseConstraint& constraint = per_pair[p];
    constraint.frame_i = pair.frame_a;
    constraint.frame_j = pair.frame_b;
    constraint.camera_j_T_camera_i = images.geometry.camera2_T_camera1;
    // The information the fit's own (widened) prior adds is not the matches': take it out.
    constraint.information = InformationFromMatches(fit_prior, images.geometry);
    if (!(constraint.information.trace() > 0)) outcomes[p] = Outcome::kNoInformation;
  });
  *counts = VisualConstraintCounts();
  std::vector<RelativePoseConstraint> constraints;
  for (int p = 0; p < n; ++p) {
    ++counts->pairs;
    switch (outcomes[p]) {
      case Outcome::kConstraint:
        constraints.push_back(per_pair[p]);
        break;
      case Outcome::kTooFewMatches:
        ++counts->too_few_matches;
        break;
      case Outcome::kTooFewInliers:
        ++counts->too_few_inliers;
        break;
      case Outcome::kInconsistentWithPrior:
        ++counts->inconsistent_with_prior;
        break;
      case Outcome::kNoInformation:
        ++counts->no_information;
        break;
    }
  }
  counts->constraints = static_cast<int>(constraints.size());
  return constraints;
}

std::vector<RelativePoseConstraint> VisualRotationSamples(const std::vector<std::pair<int, int>>& pairs,
                                                          const std::vector<MatchingDiagnostics>& diagnostics,
                                                          int min_inliers) {
  std::vector<RelativePoseConstraint> samples;
  for (size_t p = 0; p < pairs.size(); ++p) {
    const PairRefinement& refinement = diagnostics[p].refinement;
    const bool estimated = refinement.outcome == PairRefinement::Outcome::kRefined ||
                           refinement.outcome == PairRefinement::Outcome::kInconsistentWithPrior;
    if (!estimated || refinement.inliers < min_inliers) continue;
    RelativePoseConstraint sample;
    sample.frame_i = pairs[p].first;
    sample.frame_j = pairs[p].second;
    sample.camera_j_T_camera_i = refinement.estimate;
    samples.push_back(sample);
  }
  return samples;
}

}  // namespace sfm
