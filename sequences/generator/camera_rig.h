// The synthetic robot's camera: intrinsics and how it is mounted on the base.
//
// Base frame: x forward, y left, z up, origin on the floor. Camera frame (OpenCV): x right, y down,
// z forward. Unpitched, camera x = -base y, camera y = -base z, camera z = base x; `pitch` then
// tilts the optical axis down by that angle (a rotation about the camera's x axis).
#pragma once

#include <array>

#include "geometry/camera.h"
#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

struct CameraRigOptions {
  int width = 640;   // px
  int height = 480;  // px
  double fx = 450;   // px (70.8 deg horizontal field of view at 640 px)
  double fy = 450;   // px
  double cx = -1;    // px; negative: the image centre, (width - 1) / 2
  double cy = -1;    // px; negative: the image centre, (height - 1) / 2
  DistortionModel model = DistortionModel::kRadTan;  // the lens (SPEC section 1 distortion_model)
  // radtan: k1 k2 p1 p2 k3 (OpenCV order); equidistant: k1 k2 k3 k4 (cv::fisheye), the fifth 0
  std::array<double, 5> distortion{0, 0, 0, 0, 0};
  double mount_height = 1.0;   // m, camera centre above the floor
  double mount_forward = 0.2;  // m, camera centre ahead of the base origin
  double pitch = 0.05;         // rad, optical axis below the horizontal (2.9 deg)

  Status Check() const;
  // The focal length (px, fx = fy) at which the equidistant lens with these coefficients sees
  // `diagonal_rad` across the image's diagonal (corner to corner through the image centre).
  double EquidistantFocalForDiagonal(double diagonal_rad) const;
  Camera MakeCamera() const;
  Pose3 BaseTCamera() const;  // base_T_camera
};

}  // namespace sfm
