// The Ceres problems of a bundle adjustment (bundle_adjuster.h), built from the current
// parameters and landmarks: the joint problem of one solve (poses, landmarks, odometry and floor
// priors; COLMAP's BundleAdjustmentConfig and problem set-up in this problem's shape) and the
// small per-line problems on fixed poses.
#pragma once

#include <ceres/ceres.h>

#include <memory>
#include <vector>

#include "backend/bundle_adjustment/adjustment_state.h"
#include "backend/bundle_adjustment/floor_prior_state.h"
#include "backend/bundle_adjustment/line_manifold.h"
#include "backend/bundle_adjustment/pose_block_cost.h"
#include "backend/triangulation/landmarks.h"

namespace sfm {

// The robust loss on the image residuals at `scale_px` (options.robust_loss).
std::unique_ptr<ceres::LossFunction> MakeImageLoss(const BundleAdjustmentOptions& options, double scale_px);

// The poses, the landmarks and the priors of one joint solve. Each pose is one 7-number block
// (PoseBlockCost: the same residuals and Jacobian entries as two blocks, a quarter of the Schur
// complement's cells; docs/bundle_adjustment.md, "Solver"); the first is held (the gauge). With
// `with_lines` the lines are in, but those seen in exactly two views and not held by the floor
// prior, which are left to be solved alone after it (docs/bundle_adjustment.md, "Two-view lines
// apart"). The landmarks are copied into the problem; WriteLandmarks puts the solution back.
class JointProblem {
 public:
  JointProblem(const AdjustmentSetup& setup, const FloorPriorState& floor, double loss_scale_px,
               bool with_lines, AdjustmentParameters* parameters, const Landmarks& landmarks);

  // Solves until Ceres's function_tolerance; the poses, lambda and b are changed in place.
  // `callback` (optional) is told of every iteration.
  void Solve(double function_tolerance, ceres::Solver::Summary* summary,
             ceres::IterationCallback* callback = nullptr);
  // The solved points and the lines of the problem into `landmarks` (the ones it was built from).
  void WriteLandmarks(Landmarks* landmarks) const;
  // The two-view lines left out (indices into the landmarks' lines).
  const std::vector<int>& apart_lines() const { return apart_lines_; }

 private:
  void AddResidual(ceres::CostFunction* cost, ceres::LossFunction* loss, const std::vector<double*>& blocks);
  bool IsPoseRotation(const double* block) const;
  void HoldBasesOnFloor();
  std::shared_ptr<ceres::ParameterBlockOrdering> InnerIterationOrdering();
  double* point_block(size_t i) { return landmark_values_.data() + 3 * i; }
  double* line_block(size_t i) { return landmark_values_.data() + 3 * point_count_ + 6 * i; }

  const AdjustmentSetup& setup_;
  AdjustmentParameters* parameters_;
  const bool with_lines_;
  std::vector<int> joint_lines_, apart_lines_;
  size_t point_count_ = 0;
  size_t reduced_cells_ = 0;  // of the reduced system's upper triangle, for the linear solver's choice
  // Every landmark's parameters in one buffer, points then lines, in their order: Ceres orders
  // the blocks of an ordering group by address (a std::set<double*>), and that order is the
  // Schur eliminator's summation order. In a buffer it is the landmarks' order, not the heap's,
  // so that a run gives the same numbers every time.
  std::vector<double> landmark_values_;
  // Not owned by the problem, so declared before it.
  std::unique_ptr<ceres::LossFunction> loss_;
  ceres::HuberLoss floor_loss_{1.0};
  PoseManifold pose_manifold_;
  OrthonormalLineManifold line_manifold_;
  std::shared_ptr<ceres::ParameterBlockOrdering> ordering_;
  std::unique_ptr<ceres::Problem> problem_;
};

// Each line alone, the poses held where they are (one small problem per line, 4 unknowns), at the
// loss scale `loss_scale_px`. A line whose solve fails keeps its estimate. `subset`: only those
// lines (indices), else all. Returns the sum of their final costs (Ceres's, 1/2 sum of the loss).
double RefineLinesOnFixedPoses(const AdjustmentSetup& setup, double loss_scale_px,
                               std::vector<PoseParameters>* poses, Landmarks* landmarks,
                               const std::vector<int>* subset = nullptr);

}  // namespace sfm
