#include "backend/bundle_adjustment/bundle_adjustment_options.h"

#include <cmath>
#include <string>

namespace sfm {

Status BundleAdjustmentOptions::Check() const {
  auto error = [](const std::string& what) { return Status::Error("bundle adjustment options: " + what); };
  if (!(robust_loss_scale_px > 0 && std::isfinite(robust_loss_scale_px))) {
    return error("robust_loss_scale_px must be > 0 px");
  }
  if (!(coarse_loss_scale_px > 0 && std::isfinite(coarse_loss_scale_px))) {
    return error("coarse_loss_scale_px must be > 0 px");
  }
  if (max_iterations < 1) return error("max_iterations must be >= 1");
  if (!(function_tolerance > 0 && function_tolerance < 1)) return error("function_tolerance must be in (0, 1)");
  if (!(intermediate_function_tolerance > 0 && intermediate_function_tolerance < 1)) {
    return error("intermediate_function_tolerance must be in (0, 1)");
  }
  if (!(outlier_threshold_px > 0)) return error("outlier_threshold_px must be > 0 px");
  if (outlier_rounds < 0) return error("outlier_rounds must be >= 0");
  if (dense_schur_max_frames < 0) return error("dense_schur_max_frames must be >= 0");
  if (!(iterative_schur_min_cells_per_frame > 0)) {
    return error("iterative_schur_min_cells_per_frame must be > 0");
  }
  if (!(odometry_min_distance_m > 0 && std::isfinite(odometry_min_distance_m))) {
    return error("odometry_min_distance_m must be > 0 m");
  }
  if (!(min_point_triangulation_angle_deg >= 0 && min_point_triangulation_angle_deg < 90)) {
    return error("min_point_triangulation_angle_deg must be in [0, 90) deg");
  }
  if (!(min_line_triangulation_angle_deg >= 0 && min_line_triangulation_angle_deg < 90)) {
    return error("min_line_triangulation_angle_deg must be in [0, 90) deg");
  }
  if (!(min_depth_m >= 0 && std::isfinite(min_depth_m))) return error("min_depth_m must be >= 0 m");
  if (!(floor_sigma_m > 0 && std::isfinite(floor_sigma_m))) return error("floor_sigma_m must be > 0 m");
  if (floor_min_landmarks < 1) return error("floor_min_landmarks must be >= 1");
  if (floor_start_min_frames < 0) return error("floor_start_min_frames must be >= 0");
  return Status::Ok();
}

}  // namespace sfm
