#include "backend/initialization/visual_constraints.h"

#include <Eigen/Eigenvalues>

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

}  // namespace

Matrix6 InformationFromMatches(const PairGeometry& prior, const PairGeometry& posterior) {
  const Matrix6 difference = PseudoInverse(posterior.covariance) - PseudoInverse(prior.covariance);
  const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(0.5 * (difference + difference.transpose()));
  const Eigen::Matrix<double, 6, 1> values = eigen.eigenvalues().cwiseMax(0);
  return eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
}

std::vector<RelativePoseConstraint> VisualConstraints(const std::vector<std::pair<int, int>>& pairs,
                                                      const std::vector<PairGeometry>& priors,
                                                      const std::vector<MatchingDiagnostics>& diagnostics,
                                                      VisualConstraintCounts* counts) {
  *counts = VisualConstraintCounts();
  std::vector<RelativePoseConstraint> constraints;
  for (size_t p = 0; p < pairs.size(); ++p) {
    ++counts->pairs;
    const PairRefinement& refinement = diagnostics[p].refinement;
    switch (refinement.outcome) {
      case PairRefinement::Outcome::kRefined:
        break;
      case PairRefinement::Outcome::kTooFewInliers:
        ++counts->too_few_inliers;
        continue;
      case PairRefinement::Outcome::kInconsistentWithPrior:
        ++counts->inconsistent_with_prior;
        continue;
      case PairRefinement::Outcome::kTooFewMatches:
      case PairRefinement::Outcome::kNoPriorUncertainty:
        ++counts->too_few_matches;
        continue;
    }
    RelativePoseConstraint constraint;
    constraint.frame_i = pairs[p].first;
    constraint.frame_j = pairs[p].second;
    constraint.camera_j_T_camera_i = refinement.geometry.camera2_T_camera1;
    constraint.information = InformationFromMatches(priors[p], refinement.geometry);
    if (!(constraint.information.trace() > 0)) {
      ++counts->no_information;
      continue;
    }
    constraints.push_back(constraint);
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
