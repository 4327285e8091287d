// What one bundle adjustment run shares between its parts (bundle_adjuster.h): the constant set-up
// (camera model, rig, odometry prior, options) and the variables other than the landmarks (the
// poses, the odometry's scale factor and rotation bias), as Ceres parameter blocks.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/bundle_adjustment/pose_parameters.h"
#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"

namespace sfm {

// Constant through a run. `odometry` and `options` are referenced, not copied.
struct AdjustmentSetup {
  AdjustmentSetup(const Calibration& calibration, const std::vector<Pose3>& world_T_base_odometry,
                  const BundleAdjustmentOptions& adjustment_options)
      : camera(calibration.base_T_camera, calibration.camera.fx, calibration.camera.fy, calibration.camera.cx,
               calibration.camera.cy),
        base_T_camera(calibration.base_T_camera),
        K(calibration.camera.K()),
        noise(calibration.odometry_noise),
        odometry(world_T_base_odometry),
        options(adjustment_options) {}

  const CameraModel camera;
  const Pose3 base_T_camera;
  const Eigen::Matrix3d K;
  const OdometryNoise noise;
  const std::vector<Pose3>& odometry;  // world_T_base, the odometry prior's measurements
  const BundleAdjustmentOptions& options;
};

// The variables besides the landmarks, in the blocks the solves change.
struct AdjustmentParameters {
  std::vector<PoseParameters> poses;  // world_T_base per frame; the first is held (the gauge)
  // lambda, the odometry's scale factor (docs/bundle_adjustment.md, "Floor prior"): a block of the
  // problem once the floor prior frees it, or held at a start scale other than 1.
  double odometry_scale = 1;
  // b, the odometry's rotation bias (rad per step, angle-axis in base_i), when with_bias.
  std::array<double, 3> rotation_bias = {0, 0, 0};
  bool with_bias = false;   // b is in the problem (decided once for the run)
  bool hold_scale = false;  // lambda held in the joint solves (the scale line search's samples)

  std::vector<Pose3> Poses() const {
    std::vector<Pose3> world_T_base;
    world_T_base.reserve(poses.size());
    for (const PoseParameters& pose : poses) world_T_base.push_back(pose.ToPose());
    return world_T_base;
  }
};

}  // namespace sfm
