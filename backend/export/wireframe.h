// The reconstructed 3D wireframe as written to wireframe.ply (SPEC section 3).
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace sfm {

struct ReconstructedWireframe {
  // 3D junction points and segment end-points, world frame, metres.
  std::vector<Eigen::Vector3d> vertices;
  // 3D line segments as pairs of 0-based indices into `vertices`.
  std::vector<std::pair<int, int>> edges;
  // Empty, or one per vertex: the junction track (tracks.csv's track_id) a 3D junction point was
  // triangulated from, -1 for a segment end-point.
  std::vector<int> track_ids;
};

}  // namespace sfm
