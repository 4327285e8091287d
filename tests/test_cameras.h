// Cameras that several tests share.
#pragma once

#include "geometry/camera.h"

namespace sfm::testing {

// The benchmark's distorted corridor lens (docs/junction_results.md): 640 x 480, fx = 450,
// k1 = -0.25, k2 = 0.07, p1 = 0.0005, p2 = -0.0005; the undistorted image of the stored size loses
// about 50 px per side.
inline Camera BenchmarkLens() {
  Camera camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = camera.fy = 450;
  camera.cx = 319.5;
  camera.cy = 239.5;
  camera.distortion = {-0.25, 0.07, 0.0005, -0.0005, 0};
  return camera;
}

// make_sequence --lens equidistant's 150-degree fisheye: 640 x 480, f 305.6 px, k = 0.
inline Camera GeneratorFisheye() {
  Camera camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = camera.fy = 305.6;
  camera.cx = 319.5;
  camera.cy = 239.5;
  camera.model = DistortionModel::kEquidistant;
  return camera;
}

}  // namespace sfm::testing
