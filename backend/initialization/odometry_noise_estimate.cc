#include "backend/initialization/odometry_noise_estimate.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "util/median.h"

namespace sfm {
namespace {

// 1.4826 times the median absolute deviation from `centre`: the standard deviation of a normal
// sample, insensitive to a minority of outliers.
double RobustSigma(const std::vector<double>& values, double centre) {
  std::vector<double> deviations;
  deviations.reserve(values.size());
  for (double v : values) deviations.push_back(std::abs(v - centre));
  return 1.4826 * Median(deviations);
}

Eigen::Vector3d AngleAxis(const Eigen::Quaterniond& q) {
  const Eigen::AngleAxisd angle_axis(q.normalized());
  return angle_axis.angle() * angle_axis.axis();
}

}  // namespace

double OdometryRotationEstimate::EffectiveSigma() const { return std::hypot(sigma, bias.norm()); }

double OdometryTranslationEstimate::EffectiveSigma() const { return std::hypot(scale_error, distance_sigma); }

OdometryRotationEstimate EstimateOdometryRotationNoise(const std::vector<Pose3>& world_T_base_odometry,
                                                       const Pose3& base_T_camera,
                                                       const std::vector<RelativePoseConstraint>& constraints,
                                                       int min_steps) {
  std::vector<double> errors[3];
  const Pose3 camera_T_base = base_T_camera.Inverse();
  const int n = static_cast<int>(world_T_base_odometry.size());
  for (const RelativePoseConstraint& constraint : constraints) {
    if (constraint.frame_j != constraint.frame_i + 1 || constraint.frame_j >= n || constraint.frame_i < 0) continue;
    const Pose3 images = base_T_camera * constraint.camera_j_T_camera_i.Inverse() * camera_T_base;
    const Pose3 odometry =
        world_T_base_odometry[constraint.frame_i].Inverse() * world_T_base_odometry[constraint.frame_j];
    const Eigen::Vector3d error = AngleAxis(odometry.rotation * images.rotation.conjugate());
    for (int k = 0; k < 3; ++k) errors[k].push_back(error[k]);
  }
  OdometryRotationEstimate estimate;
  estimate.steps = static_cast<int>(errors[0].size());
  if (estimate.steps < min_steps) return estimate;
  estimate.valid = true;
  for (int k = 0; k < 3; ++k) {
    estimate.bias[k] = Median(errors[k]);
    estimate.axis_sigmas[k] = RobustSigma(errors[k], estimate.bias[k]);
    estimate.sigma = std::max(estimate.sigma, estimate.axis_sigmas[k]);
  }
  return estimate;
}

OdometryTranslationEstimate EstimateOdometryTranslationNoise(const std::vector<Pose3>& world_T_base_odometry,
                                                             const std::vector<Pose3>& world_T_base,
                                                             double min_step_m, int min_steps) {
  std::vector<double> ratios;
  const size_t n = std::min(world_T_base_odometry.size(), world_T_base.size());
  for (size_t k = 0; k + 1 < n; ++k) {
    const double odometry = (world_T_base_odometry[k + 1].translation - world_T_base_odometry[k].translation).norm();
    const double step = (world_T_base[k + 1].translation - world_T_base[k].translation).norm();
    if (odometry < min_step_m || step < min_step_m) continue;
    ratios.push_back(odometry / step);
  }
  OdometryTranslationEstimate estimate;
  estimate.steps = static_cast<int>(ratios.size());
  if (estimate.steps < min_steps) return estimate;
  estimate.valid = true;
  const double median = Median(ratios);
  estimate.scale_error = median - 1;
  estimate.distance_sigma = RobustSigma(ratios, median) / median;
  return estimate;
}

bool DeclaredSigmaContradicted(double declared, double estimated, double factor) {
  if (!(declared > 0 && estimated > 0)) return false;
  return declared > factor * estimated || estimated > factor * declared;
}

}  // namespace sfm
