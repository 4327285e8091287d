// What the back end works on (COLMAP's Reconstruction, in this problem's shape): the rig, every
// frame's pose, the junctions the tracks refer to, the tracks and the landmarks triangulated from
// them. The track extension (track_extension.h) and the bundle adjustment
// (backend/bundle_adjustment/bundle_adjuster.h) change it in place.
#pragma once

#include <vector>

#include "backend/triangulation/landmarks.h"
#include "geometry/pose.h"
#include "frontend/junctions/junction.h"
#include "frontend/sequence/sequence.h"
#include "frontend/tracks/tracks.h"

namespace sfm {

struct Reconstruction {
  Calibration calibration;           // K (undistorted pixels), base_T_camera, odometry noise
  std::vector<Pose3> world_T_base;   // per frame
  std::vector<Junctions> junctions;  // per frame, undistorted pixels
  std::vector<JunctionTrack> tracks;
  Landmarks landmarks;

  // world_T_camera of every frame: world_T_base * base_T_camera.
  std::vector<Pose3> WorldTCamera() const {
    std::vector<Pose3> cameras;
    cameras.reserve(world_T_base.size());
    for (const Pose3& pose : world_T_base) cameras.push_back(pose * calibration.base_T_camera);
    return cameras;
  }
};

}  // namespace sfm
