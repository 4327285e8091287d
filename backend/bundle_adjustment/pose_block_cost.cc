#include "backend/bundle_adjustment/pose_block_cost.h"

#include <glog/logging.h>

#include <algorithm>
#include <array>

namespace sfm {

PoseBlockCost::PoseBlockCost(ceres::CostFunction* inner, const std::vector<int>& pose_starts)
    : inner_(inner) {
  const std::vector<int32_t>& sizes = inner_->parameter_block_sizes();
  CHECK_LE(sizes.size(), static_cast<size_t>(kMaxInnerBlocks));
  CHECK_LE(static_cast<int>(pose_starts.size()) * 7 * inner_->num_residuals(), kScratchSize);
  set_num_residuals(inner_->num_residuals());
  std::vector<int32_t>* outer_sizes = mutable_parameter_block_sizes();
  for (int k = 0; k < static_cast<int>(sizes.size()); ++k) {
    const bool pose = std::find(pose_starts.begin(), pose_starts.end(), k) != pose_starts.end();
    if (pose) CHECK(k + 1 < static_cast<int>(sizes.size()) && sizes[k] == 4 && sizes[k + 1] == 3);
    first_inner_block_.push_back(k);
    is_pose_.push_back(pose);
    outer_sizes->push_back(pose ? 7 : sizes[k]);
    if (pose) ++k;
  }
}

bool PoseBlockCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  std::array<const double*, kMaxInnerBlocks> inner_parameters{};
  for (size_t o = 0; o < is_pose_.size(); ++o) {
    const int k = first_inner_block_[o];
    inner_parameters[k] = parameters[o];
    if (is_pose_[o]) inner_parameters[k + 1] = parameters[o] + 4;
  }
  if (jacobians == nullptr) return inner_->Evaluate(inner_parameters.data(), residuals, nullptr);

  const int rows = num_residuals();
  std::array<double, kScratchSize> scratch;
  std::array<double*, kMaxInnerBlocks> inner_jacobians{};
  int used = 0;
  for (size_t o = 0; o < is_pose_.size(); ++o) {
    const int k = first_inner_block_[o];
    if (!is_pose_[o]) {
      inner_jacobians[k] = jacobians[o];
    } else if (jacobians[o] != nullptr) {
      inner_jacobians[k] = scratch.data() + used;
      inner_jacobians[k + 1] = scratch.data() + used + 4 * rows;
      used += 7 * rows;
    }
  }
  if (!inner_->Evaluate(inner_parameters.data(), residuals, inner_jacobians.data())) return false;
  // Row-major rows x 4 and rows x 3 side by side into rows x 7.
  for (size_t o = 0; o < is_pose_.size(); ++o) {
    if (!is_pose_[o] || jacobians[o] == nullptr) continue;
    const int k = first_inner_block_[o];
    for (int r = 0; r < rows; ++r) {
      std::copy(inner_jacobians[k] + 4 * r, inner_jacobians[k] + 4 * r + 4, jacobians[o] + 7 * r);
      std::copy(inner_jacobians[k + 1] + 3 * r, inner_jacobians[k + 1] + 3 * r + 3, jacobians[o] + 7 * r + 4);
    }
  }
  return true;
}

}  // namespace sfm
