// What the images say about a trajectory, without ground truth (docs/initialization.md, "The
// run's own evidence"): how well each matched pair's junctions fit the epipolar geometry the
// trajectory gives the pair, and where the trajectory departs from the odometry by more than the
// odometry's noise allows. The run compares the refined trajectory with the odometry by these
// and says so when its evidence favours the odometry.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "geometry/pose.h"
#include "frontend/junctions/junction.h"
#include "frontend/sequence/sequence.h"
#include "frontend/tracks/tracks.h"

namespace sfm {

// The median over the matched pairs of each pair's median |Sampson distance| (pixels) of its
// matches under the relative pose world_T_camera gives the pair (K of the undistorted images). A
// trajectory the images agree with scores near the junction location noise. NaN without a pair.
double EpipolarEvidencePx(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const std::vector<Junctions>& junctions, const std::vector<FramePairMatches>& pairs);

// The frames k whose step k-1 -> k of world_T_base departs from the odometry's by more than
// num_sigmas of the noise model: rotation angle beyond num_sigmas * rotation_sigma, or the
// step's translation beyond num_sigmas * hypot(translation_sigma, rotation_sigma) * max(distance,
// min_distance_m) (its length by the distance noise, its direction by the heading noise).
std::vector<int> FramesDisagreeingWithOdometry(const std::vector<Pose3>& world_T_base_odometry,
                                               const std::vector<Pose3>& world_T_base, const OdometryNoise& noise,
                                               double min_distance_m, double num_sigmas = 3);

}  // namespace sfm
