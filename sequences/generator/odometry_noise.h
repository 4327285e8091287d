// Simulated wheel odometry: the true motion between consecutive frames, corrupted the way wheel
// encoders and a gyro-less heading integration corrupt it, then integrated from the true first
// pose (so odometry and ground truth share one world frame, as SPEC section 1 expects).
//
// Model, per frame i -> i+1 with true relative motion (R_i, t_i) = base_i_T_base_{i+1}:
//   t'_i = (1 + scale_error) * (1 + distance_sigma * n1) * t_i
//   R'_i = Rz(heading_bias + heading_sigma * n2) * R_i
// with n1, n2 independent standard normal draws (both drawn every frame, so turning one noise off
// leaves the other's numbers unchanged). odom_0 = true_0, odom_{i+1} = odom_i * (R'_i, t'_i).
// scale_error is a wheel-radius calibration error; heading_bias a wheel-base error or a slightly
// unequal wheel pair; heading_sigma and distance_sigma wheel slip.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"
#include "util/status.h"

namespace sfm {

struct OdometryNoiseOptions {
  double scale_error = 0.02;     // fraction: odometry reports (1 + scale_error) x the true distance
  double distance_sigma = 0.01;  // fraction of each step's distance, Gaussian sigma
  double heading_sigma = 0.002;  // rad per frame, Gaussian sigma
  double heading_bias = 0.001;   // rad per frame, added to every frame's heading change (left > 0)

  Status Check() const;
  // The model as sequence.yaml states it (SPEC section 1): translation sigma
  // sqrt(scale_error^2 + distance_sigma^2) as a fraction of the distance, rotation sigma
  // sqrt(heading_sigma^2 + heading_bias^2) per frame; floored at 1e-4 and 1e-5 so that a reader
  // weighting the odometry by 1/sigma stays finite for noise-free sequences.
  OdometryNoise ForCalibration() const;
};

// Odometry poses world_T_base for the true poses, from `seed` alone.
std::vector<Pose3> SimulateOdometry(const std::vector<Pose3>& world_T_base_true, const OdometryNoiseOptions& options,
                                    std::uint64_t seed);

}  // namespace sfm
