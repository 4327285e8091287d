// A frame's pose as one Ceres parameter block for the joint solves.
//
// The cost functions take a pose as two blocks, rotation[4] and translation[3] (pose_parameters.h).
// Ceres's Schur eliminator forms one cell of the reduced (pose) system per pair of pose blocks that
// a landmark's views share, and with its generic eliminator (points and lines mixed in the
// eliminated group) each cell is a small product of run-time size under a lock: with the two
// blocks a frame has four cells where one 7-number block has one of twice the width, the same
// arithmetic in a quarter of the cells (docs/bundle_adjustment.md, "Solver").
// PoseBlockCost presents an unchanged cost function to Ceres with each (rotation, translation)
// pair replaced by one block [qx qy qz qw tx ty tz], PoseParameters's own layout; PoseManifold is
// the quaternion's manifold times R^3 (tangent 6). Same residuals and Jacobian entries: they are
// copied, not recomputed.
#pragma once

#include <ceres/cost_function.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>

#include <cstddef>
#include <memory>
#include <vector>

#include "backend/bundle_adjustment/pose_parameters.h"

namespace sfm {

using PoseManifold = ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>>;

// The one-block view of a pose needs its translation right after its rotation.
static_assert(offsetof(PoseParameters, translation) == 4 * sizeof(double),
              "PoseParameters must hold rotation[4] and translation[3] contiguously");

class PoseBlockCost final : public ceres::CostFunction {
 public:
  // `inner`'s parameter blocks k (size 4) and k + 1 (size 3), for each k of `pose_starts`, are one
  // pose's rotation and translation; they become one block of 7. Takes ownership of `inner`.
  PoseBlockCost(ceres::CostFunction* inner, const std::vector<int>& pose_starts);

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  // Room for the inner Jacobians of the pose blocks, residuals x 7 per pose (the odometry priors:
  // 6 residuals, 2 poses).
  static constexpr int kScratchSize = 96;
  static constexpr int kMaxInnerBlocks = 8;

  std::unique_ptr<ceres::CostFunction> inner_;
  std::vector<int> first_inner_block_;  // per outer block: its (first) inner block
  std::vector<bool> is_pose_;           // per outer block
};

}  // namespace sfm
