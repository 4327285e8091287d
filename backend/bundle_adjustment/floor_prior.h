// When the ground-plane (floor) prior applies, and which landmarks it holds: the rules of
// docs/bundle_adjustment.md, "Floor prior". The residuals are in floor_prior_cost.h; the bundle
// adjuster calls these checks and selections between its stages.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "backend/triangulation/landmarks.h"
#include "geometry/pose.h"

namespace sfm {

// The rig and the odometry: why the floor prior cannot apply, or "" when it can. The camera must
// be at least 10 sigma_m above the base origin (base_T_camera's z); every odometry pose's z within
// sigma_m of 0 and its base tilted (roll/pitch: the angle of its z axis from the world's) by at
// most sigma_m / camera height, the tilt that moves the floor under the camera by sigma_m.
std::string FloorPriorRigProblem(const Pose3& base_T_camera, const std::vector<Pose3>& world_T_base_odometry,
                                 double sigma_m);

struct FloorPlane {
  bool found = false;
  double z_m = 0;     // world height of the slab's centre
  int support = 0;    // landmarks in the slab
  int below_camera = 0;  // landmarks considered (heights below the cameras)
  std::string why;    // when not found: why not
};

// Points marked occlusion_candidate (seen as a T or an X: possibly where a nearer edge crosses the
// floor's edge, a "point" between the two depths, above the floor) are never floor landmarks, here
// or in SelectFloorLandmarks.
// The floor: the lowest horizontal slab [z - half_width_m, z + half_width_m] below camera_z_m
// that holds at least `min_support` landmarks (nothing is seen below a floor, except a few
// mis-triangulated landmarks, which do not gather in one slab). A landmark's height: a point's z;
// a line's mean end z when its two ends differ by at most half_width_m in z (a horizontal line),
// otherwise it is not considered. With `around_z_m` the slab is not searched from below but
// started there (and moved to the median of what it holds, as above): on a map the floor prior
// has already pulled to that height, a group of `min_support` stray landmarks further down must
// not replace the floor it holds.
// With `lowest_z_m`, heights below it are not considered (the search from below starts there).
FloorPlane FindFloorPlane(const Landmarks& landmarks, double camera_z_m, double half_width_m, int min_support,
                          std::optional<double> around_z_m = std::nullopt,
                          std::optional<double> lowest_z_m = std::nullopt);

struct FloorLandmarks {
  std::vector<int> points;  // indices into Landmarks::points
  std::vector<int> lines;   // indices into Landmarks::lines (both ends in the slab)
};

// The landmarks within half_width_m of height plane_z_m (lines: both ends).
FloorLandmarks SelectFloorLandmarks(const Landmarks& landmarks, double plane_z_m, double half_width_m);

// The gain that scales a map about a camera centre at height camera_z_m so that a floor plane
// found at plane_z_m goes to z = 0: camera_z_m / (camera_z_m - plane_z_m). A map whose trajectory
// is s times too long has its floor at (1 - s) camera_z_m, so this gain is 1 / s. 1 when the plane
// is not below the camera.
double FloorScaleGain(double camera_z_m, double plane_z_m);

// Every landmark (points; lines' point, end0 and end1; directions unchanged) scaled by `gain`
// about `centre`.
void ScaleLandmarksAbout(const Eigen::Vector3d& centre, double gain, Landmarks* landmarks);

// The minimum of the parabola through three costs sampled one step apart (at -1, 0, +1 steps), in
// steps, clamped to [-max_steps, max_steps]; when the parabola is not convex, the step of the
// lowest sample (-1, 0 or +1; 0 on ties with the centre).
double ParabolaMinimumStep(double cost_below, double cost_centre, double cost_above, double max_steps);

}  // namespace sfm
