#include "backend/initialization/trajectory_evidence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/epipolar.h"
#include "frontend/matching/pair_refinement.h"
#include "util/median.h"

namespace sfm {

double EpipolarEvidencePx(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const std::vector<Junctions>& junctions, const std::vector<FramePairMatches>& pairs) {
  std::vector<double> per_pair;
  for (const FramePairMatches& pair : pairs) {
    if (pair.matches.empty()) continue;
    const Eigen::Matrix3d F = FundamentalFromPoses(K, world_T_camera[pair.frame_a], world_T_camera[pair.frame_b]);
    std::vector<double> distances;
    distances.reserve(pair.matches.size());
    for (const JunctionMatch& match : pair.matches) {
      distances.push_back(std::abs(SampsonDistance(F, junctions[pair.frame_a][match.index_a].location,
                                                   junctions[pair.frame_b][match.index_b].location)));
    }
    per_pair.push_back(Median(std::move(distances)));
  }
  return Median(std::move(per_pair));
}

std::vector<int> FramesDisagreeingWithOdometry(const std::vector<Pose3>& world_T_base_odometry,
                                               const std::vector<Pose3>& world_T_base, const OdometryNoise& noise,
                                               double min_distance_m, double num_sigmas) {
  std::vector<int> frames;
  const size_t n = std::min(world_T_base_odometry.size(), world_T_base.size());
  for (size_t k = 1; k < n; ++k) {
    const Pose3 odometry = world_T_base_odometry[k - 1].Inverse() * world_T_base_odometry[k];
    const Pose3 step = world_T_base[k - 1].Inverse() * world_T_base[k];
    const double rotation = RotationAngle(odometry.rotation, step.rotation);
    const double translation = (odometry.translation - step.translation).norm();
    const double distance = std::max(odometry.translation.norm(), min_distance_m);
    if (rotation > num_sigmas * noise.rotation_sigma ||
        translation > num_sigmas * std::hypot(noise.translation_sigma, noise.rotation_sigma) * distance) {
      frames.push_back(static_cast<int>(k));
    }
  }
  return frames;
}

}  // namespace sfm
