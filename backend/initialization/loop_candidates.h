// Loop closure candidates: pairs of frames far apart along the trajectory whose views overlap on
// the current pose estimate (docs/initialization.md, "Loop closure"). The pipeline matches them
// like any pair (the paper's similarity, topology and rule 38) under the pose estimate's
// uncertainty over the frames between them, and keeps those whose matches give a relative pose.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "backend/triangulation/landmarks.h"
#include "geometry/pose.h"

namespace sfm {

struct LoopCandidateOptions {
  // A revisit: the path travelled between the two frames at least this many times the distance
  // between their cameras (a camera that moved straight on is not back anywhere).
  double min_path_over_distance = 3;
  // Least number of a frame's points that must project into the other frame (in front of it,
  // inside the image): below it the overlap is too small to give a relative pose.
  int min_points_in_view = 15;
  // Least share of frame a's points that project into frame b.
  double min_share_in_view = 0.5;
  // Pairs already linked by the tracks (a share of the points in view seen in both frames at
  // least this) are not loops: the tracks hold them together.
  double max_share_already_tracked = 0.2;
  // Depth below which a projection is not counted, metres.
  double min_depth_m = 0.1;
  // Each frame takes part in at most this many candidate pairs, and there are at most
  // num_frames / frames_per_candidate of them (the matching's cost stays a fraction of the run's).
  int max_pairs_per_frame = 1;
  int frames_per_candidate = 6;
};

// Candidate pairs (a, b), a < b - 2 (nearer pairs are matched anyway), in frame order, chosen
// greedily by overlap (the smaller of the two frames' counts of points in the other's view). world_T_camera: the current pose estimate; K, width, height: the
// undistorted camera; landmarks: the points triangulated on world_T_camera, with their views.
std::vector<std::pair<int, int>> LoopCandidates(const Eigen::Matrix3d& K, int width, int height,
                                                const std::vector<Pose3>& world_T_camera, const Landmarks& landmarks,
                                                const LoopCandidateOptions& options = LoopCandidateOptions());

}  // namespace sfm
