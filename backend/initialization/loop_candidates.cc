#include "backend/initialization/loop_candidates.h"

#include <algorithm>
#include <tuple>

namespace sfm {
namespace {

// The points of frame `from` that project into frame `to` (in front of it, inside the image), and
// how many of those `to` already sees.
struct Overlap {
  int in_view = 0;
  int tracked = 0;
};

Overlap PointsInView(const Eigen::Matrix3d& K, int width, int height, const Pose3& camera_T_world,
                     const Landmarks& landmarks, const std::vector<int>& points_of_from,
                     const std::vector<char>& seen_by_to, double min_depth_m) {
  Overlap overlap;
  for (int i : points_of_from) {
    const Eigen::Vector3d p = camera_T_world * landmarks.points[i].position;
    if (!(p.z() > min_depth_m)) continue;
    const Eigen::Vector3d x = K * (p / p.z());
    if (x.x() < 0 || x.y() < 0 || x.x() > width || x.y() > height) continue;
    ++overlap.in_view;
    if (seen_by_to[i]) ++overlap.tracked;
  }
  return overlap;
}

}  // namespace

std::vector<std::pair<int, int>> LoopCandidates(const Eigen::Matrix3d& K, int width, int height,
                                                const std::vector<Pose3>& world_T_camera, const Landmarks& landmarks,
                                                const LoopCandidateOptions& options) {
  const int n = static_cast<int>(world_T_camera.size());
  std::vector<std::vector<int>> points_of_frame(n);
  for (size_t i = 0; i < landmarks.points.size(); ++i) {
    for (const PointObservation& observation : landmarks.points[i].observations) {
      if (observation.frame >= 0 && observation.frame < n) points_of_frame[observation.frame].push_back(static_cast<int>(i));
    }
  }
  std::vector<double> path(n, 0);
  for (int f = 1; f < n; ++f) {
    path[f] = path[f - 1] + (world_T_camera[f].translation - world_T_camera[f - 1].translation).norm();
  }
  std::vector<Pose3> camera_T_world;
  camera_T_world.reserve(n);
  for (const Pose3& pose : world_T_camera) camera_T_world.push_back(pose.Inverse());

  // (overlap, a, b) of every pair that qualifies.
  std::vector<std::tuple<int, int, int>> scored;
  std::vector<char> seen_by_a(landmarks.points.size()), seen_by_b(landmarks.points.size());
  for (int a = 0; a < n; ++a) {
    if (static_cast<int>(points_of_frame[a].size()) < options.min_points_in_view) continue;
    for (int i : points_of_frame[a]) seen_by_a[i] = 1;
    for (int b = a + 3; b < n; ++b) {
      if (static_cast<int>(points_of_frame[b].size()) < options.min_points_in_view) continue;
      const double distance = (world_T_camera[b].translation - world_T_camera[a].translation).norm();
      if (!(path[b] - path[a] >= options.min_path_over_distance * distance)) continue;
      for (int i : points_of_frame[b]) seen_by_b[i] = 1;
      const Overlap a_in_b =
          PointsInView(K, width, height, camera_T_world[b], landmarks, points_of_frame[a], seen_by_b, options.min_depth_m);
      const Overlap b_in_a =
          PointsInView(K, width, height, camera_T_world[a], landmarks, points_of_frame[b], seen_by_a, options.min_depth_m);
      for (int i : points_of_frame[b]) seen_by_b[i] = 0;
      const int in_view = std::min(a_in_b.in_view, b_in_a.in_view);
      if (in_view < options.min_points_in_view) continue;
      if (a_in_b.in_view < options.min_share_in_view * points_of_frame[a].size() ||
          b_in_a.in_view < options.min_share_in_view * points_of_frame[b].size()) {
        continue;
      }
      if (a_in_b.tracked > options.max_share_already_tracked * a_in_b.in_view) continue;
      scored.emplace_back(in_view, a, b);
    }
    for (int i : points_of_frame[a]) seen_by_a[i] = 0;
  }
  // Greedy, largest overlap first; ties in frame order, so the choice does not depend on the
  // sort's implementation.
  std::sort(scored.begin(), scored.end(), [](const auto& x, const auto& y) {
    return std::get<0>(x) != std::get<0>(y) ? std::get<0>(x) > std::get<0>(y)
                                            : std::make_pair(std::get<1>(x), std::get<2>(x)) <
                                                  std::make_pair(std::get<1>(y), std::get<2>(y));
  });
  const size_t max_pairs = static_cast<size_t>(std::max(1, n / std::max(1, options.frames_per_candidate)));
  std::vector<int> uses(n, 0);
  std::vector<std::pair<int, int>> chosen;
  for (const auto& [overlap, a, b] : scored) {
    if (chosen.size() >= max_pairs) break;
    if (uses[a] >= options.max_pairs_per_frame || uses[b] >= options.max_pairs_per_frame) continue;
    ++uses[a];
    ++uses[b];
    chosen.emplace_back(a, b);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

}  // namespace sfm
