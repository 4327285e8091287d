// Simulated odometry for data sets that have none: the true relative camera motions, corrupted in
// the camera frame, integrated from the true first pose (so odometry and ground truth share one
// world frame, as SPEC section 1 expects).
//
// The generator's wheel-odometry model (sequences/generator/odometry_noise.h) needs a robot base
// with a known floor plane; the real data sets give camera poses only (z forward, no known up), so
// here the noise acts on each relative camera motion (R_i, t_i) = camera_i_T_camera_{i+1}:
//   t'_i = (1 + scale_error) * (1 + distance_sigma * n1) * t_i
//   R'_i = Exp(rotation_bias * e_y + rotation_sigma * (n2, n3, n4)) * R_i
// with n1..n4 independent standard normal draws (all four drawn every frame, so turning one noise
// off leaves the others' numbers unchanged) and e_y the camera's y axis, which is close to vertical
// for a forward-looking robot camera: the bias is a steady heading drift. Exp maps a rotation
// vector to a rotation. odom_0 = true_0, odom_{i+1} = odom_i * (R'_i, t'_i).
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"
#include "util/status.h"

namespace sfm {

struct CameraOdometryNoiseOptions {
  double scale_error = 0.03;      // fraction: odometry reports (1 + scale_error) x each true translation
  double distance_sigma = 0.01;   // fraction of each step's translation, Gaussian sigma
  double rotation_sigma = 0.0052; // rad per frame, Gaussian sigma of each rotation-vector component (0.3 deg)
  double rotation_bias = 0.0017;  // rad per frame about the camera's y axis (0.1 deg)

  Status Check() const;
  // The model as sequence.yaml states it (SPEC section 1): translation sigma
  // sqrt(scale_error^2 + distance_sigma^2) as a fraction of the distance, rotation sigma
  // sqrt(rotation_sigma^2 + rotation_bias^2) per frame; floored at 1e-4 and 1e-5 as the generator
  // does, so that a reader weighting the odometry by 1/sigma stays finite for noise-free odometry.
  OdometryNoise ForCalibration() const;
};

// Odometry poses world_T_camera for the true poses, a function of `seed` alone (sfm::Random, so the
// same bits on every platform).
std::vector<Pose3> SimulateCameraOdometry(const std::vector<Pose3>& world_T_camera_true,
                                          const CameraOdometryNoiseOptions& options, std::uint64_t seed);

}  // namespace sfm
