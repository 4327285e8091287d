// The one translation unit that instantiates the automatic derivatives of the cost functors.
#include <ceres/autodiff_cost_function.h>
#include <glog/logging.h>

#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/odometry_prior_cost.h"
#include "backend/bundle_adjustment/point_reprojection_cost.h"

namespace sfm {

ceres::CostFunction* PointReprojectionCost::Create(const CameraModel& camera,
                                                   const Eigen::Vector2d& observed_px) {
  return new ceres::AutoDiffCostFunction<PointReprojectionCost, 2, 4, 3, 3>(
      new PointReprojectionCost(camera, observed_px));
}

ceres::CostFunction* LineReprojectionCost::Create(const CameraModel& camera, const Eigen::Vector2d& p0_px,
                                                  const Eigen::Vector2d& p1_px) {
  return new ceres::AutoDiffCostFunction<LineReprojectionCost, 2, 4, 3, 6>(
      new LineReprojectionCost(camera, p0_px, p1_px));
}

ceres::CostFunction* OdometryPriorCost::Create(const Pose3& base_i_T_base_j_odometry,
                                               double rotation_sigma_rad, double translation_sigma_m) {
  CHECK_GT(rotation_sigma_rad, 0);
  CHECK_GT(translation_sigma_m, 0);
  return new ceres::AutoDiffCostFunction<OdometryPriorCost, 6, 4, 3, 4, 3>(
      new OdometryPriorCost(base_i_T_base_j_odometry, rotation_sigma_rad, translation_sigma_m));
}

}  // namespace sfm
