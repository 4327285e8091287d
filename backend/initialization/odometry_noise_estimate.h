// The odometry's noise measured against the images (docs/initialization.md, "Odometry noise from
// the data"): sequence.yaml's sigmas are often unknown or wrong, and the matcher's gates, the pose
// graph and the bundle adjustment's prior all weigh the odometry by them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "backend/initialization/pose_graph.h"
#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"

namespace sfm {

struct OdometryRotationEstimate {
  bool valid = false;
  int steps = 0;  // consecutive pairs whose visual rotation entered the estimate
  // The odometry's constant rotation increment per frame (angle-axis, base axes, radians): the
  // median over the steps of Log(R_odometry R_images^T).
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  // Robust standard deviation (1.4826 median absolute deviation) about the bias of the noisier
  // axis, radians per frame: the per-axis sigma of sequence.yaml's random-walk model.
  double sigma = 0;
  // The same per axis, radians per frame.
  Eigen::Vector3d axis_sigmas = Eigen::Vector3d::Zero();
  // The sigma to weigh the odometry by when its bias is not modelled: sqrt(sigma^2 + |bias|^2),
  // the spread of one step's rotation error about zero.
  double EffectiveSigma() const;
};

// From the consecutive-frame constraints (frame_j = frame_i + 1) among `constraints`; needs at
// least `min_steps` of them, else invalid. Each step's visual base motion is
// base_T_camera camera_i_T_camera_j camera_T_base.
OdometryRotationEstimate EstimateOdometryRotationNoise(const std::vector<Pose3>& world_T_base_odometry,
                                                       const Pose3& base_T_camera,
                                                       const std::vector<RelativePoseConstraint>& constraints,
                                                       int min_steps = 8);

struct OdometryTranslationEstimate {
  bool valid = false;
  int steps = 0;  // steps longer than the floor that entered the estimate
  // The odometry's distances against the trajectory's: median of |odometry step| / |step| - 1.
  double scale_error = 0;
  // Robust standard deviation of that ratio about its median: the distance noise as a fraction of
  // the distance travelled.
  double distance_sigma = 0;
  // sqrt(scale_error^2 + distance_sigma^2): the fraction of sequence.yaml's
  // odometry_translation_sigma, whose random walk holds both.
  double EffectiveSigma() const;
};

// Step lengths of the odometry against a trajectory that the images determined at the odometry's
// scale (the bundle adjustment's refined base poses); steps shorter than min_step_m in either are
// left out (their ratio is slip). Needs at least `min_steps` steps, else invalid.
OdometryTranslationEstimate EstimateOdometryTranslationNoise(const std::vector<Pose3>& world_T_base_odometry,
                                                             const std::vector<Pose3>& world_T_base,
                                                             double min_step_m, int min_steps = 8);

// Whether a declared sigma and its estimate from the data disagree by more than `factor` either
// way (then the run warns).
bool DeclaredSigmaContradicted(double declared, double estimated, double factor = 2.0);

}  // namespace sfm
