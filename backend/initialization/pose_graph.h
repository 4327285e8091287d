// The initial trajectory: the odometry and the images' relative poses fused by their
// uncertainties in a pose graph (docs/initialization.md), before anything is triangulated, so the
// triangulation and the bundle adjustment start from poses the images agree with instead of the
// drifted odometry.
//
// Unknowns: world_T_base of every frame (the first held, fixing the gauge). Factors:
//  - the odometry prior of every consecutive step (the bundle adjustment's OdometryPriorCost),
//    weighted by the odometry noise model it is given, with the odometry's constant rotation
//    increment per step b (a wheel-base error turns every step by the same angle) solved for
//    under a zero-mean prior of the rotation sigma: over a stretch where the images say little, the
//    odometry's drift is then only its random part;
//  - one factor per image pair whose relative pose the images determined (RelativePoseConstraint),
//    weighted by the information the pair's matches alone carry about the pose, under a Cauchy
//    loss so that a pair estimated on wrong matches loses its pull.
// A monocular pair carries no information on its translation's length: the odometry sets the
// scale, the images the rotations and the directions of travel.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"
#include "util/status.h"

namespace sfm {

// What a pair of images says about its relative pose: camera_j_T_camera_i with the information
// (inverse covariance) of the perturbation xi = (omega, dt) of PairGeometry: the true pose is
// (Exp(omega) R, t + dt), omega in radians in camera j's axes, dt in metres.
struct RelativePoseConstraint {
  int frame_i = 0;
  int frame_j = 0;  // > frame_i
  Pose3 camera_j_T_camera_i;
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();  // symmetric PSD
  // false for a loop closure: its pose was gated against the trajectory's uncertainty over all
  // the frames between the two, so the pose graph's Cauchy loss, which would read the drift it
  // corrects as its own error, is not applied.
  bool robust = true;
};

struct PoseGraphOptions {
  // Cauchy loss on each relative pose factor, in units of its whitened residual norm: a pair whose
  // estimate disagrees with the rest by more than a few of its sigmas is a wrong estimate.
  double loss_scale_sigmas = 3.0;
  int max_iterations = 100;
  // The odometry's rotation noise per base axis (rad per step, the spread about the bias); where
  // a component is not positive, odometry_noise.rotation_sigma.
  Eigen::Vector3d rotation_sigmas = Eigen::Vector3d::Zero();
  // Where b starts (e.g. OdometryRotationEstimate::bias), rad per step, angle-axis in the base frame.
  Eigen::Vector3d rotation_bias_start = Eigen::Vector3d::Zero();
};

struct PoseGraphSummary {
  int constraints = 0;
  // Relative pose factors whose whitened residual is beyond loss_scale_sigmas at the solution.
  int constraints_rejected = 0;
  double initial_cost = 0;
  double final_cost = 0;
  int iterations = 0;
  Eigen::Vector3d rotation_bias = Eigen::Vector3d::Zero();  // b at the solution
};

// The fused trajectory, solved from the odometry's steps with those of consecutive pairs replaced
// by the images'. `odometry_noise` weighs the odometry prior
// (its rotation sigma the spread of a step's rotation about the bias)
// (with options.odometry_min_distance_m of `adjustment` as for the bundle adjustment), `base_T_camera`
// turns the camera constraints into base poses. world_T_base_odometry has at least one pose;
// constraint indices lie within it.
Status SolvePoseGraph(const std::vector<Pose3>& world_T_base_odometry, const Pose3& base_T_camera,
                      const OdometryNoise& odometry_noise, const BundleAdjustmentOptions& adjustment,
                      const std::vector<RelativePoseConstraint>& constraints, const PoseGraphOptions& options,
                      std::vector<Pose3>* world_T_base, PoseGraphSummary* summary);

}  // namespace sfm
