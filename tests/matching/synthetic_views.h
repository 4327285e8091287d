// Two calibrated views of 3D junctions for the matching tests: projection, clockwise ordering,
// F from the relative pose, and end-point perturbation.
#pragma once

#include <random>
#include <vector>

#include <Eigen/Core>

#include "geometry/pose.h"
#include "frontend/junctions/junction.h"

namespace sfm::testing {

// A 3D junction: a point and the far ends of its arms (metres, world frame).
struct Junction3d {
  Eigen::Vector3d location;
  std::vector<Eigen::Vector3d> ends;
};

struct TwoViews {
  Eigen::Matrix3d K;
  Pose3 world_T_camera1;
  Pose3 world_T_camera2;
  int width = 640;
  int height = 480;

  // x2^T F x1 = 0: F = K^-T [t]x R K^-1 with camera2_T_camera1 = (R, t) (docs/conventions.md),
  // computed here rather than by sfm_geometry so that the tests check the matcher against an
  // independent F.
  Eigen::Matrix3d F() const;
  // Pixel of a world point in camera 1 or 2 (camera = 0 or 1).
  Eigen::Vector2d Project(int camera, const Eigen::Vector3d& point_world) const;
};

// A robot-like pair: camera 2 moved 0.3 m forward and 0.1 m sideways, turned 3 degrees.
TwoViews MakeTwoViews();

// The image of a 3D junction in one camera, segments clockwise on screen (increasing atan2(dy, dx),
// y down). arm_of_segment[k]: the 3D arm segment k comes from.
struct ProjectedJunction {
  Junction junction;
  std::vector<int> arm_of_segment;
};
ProjectedJunction ProjectJunction(const TwoViews& views, int camera, const Junction3d& junction3d);

// Every segment of the image junction at least min_length_px long, inside the image, and every
// two neighbouring segments at least min_angle_deg apart.
bool IsWellShaped(const Junction& junction, const TwoViews& views, double min_length_px, double min_angle_deg);

// Moves each end-point along its segment by a uniform amount in [min_px, max_px] (positive:
// longer) and the location by Gaussian noise of sigma location_sigma_px in each axis.
void Perturb(Junction* junction, double min_px, double max_px, double location_sigma_px, std::mt19937* rng);

// A random 3D junction with num_arms arms of 0.4-1 m in front of camera 1, whose images in both
// cameras are well shaped (20 px, 25 degrees).
Junction3d RandomJunction3d(const TwoViews& views, int num_arms, std::mt19937* rng);

// True when two segments of the junction point opposite ways within max_deg: a line through its
// location, as junction detection reads a T's bar.
bool HasLineThrough(const Junction& junction, double max_deg);

// Segment correspondence between two images of one 3D junction as the shift of eq. (32): segment i
// of a is segment (i + shift) mod N of b; -1 if they are not a cyclic shift of each other.
int TrueShift(const ProjectedJunction& a, const ProjectedJunction& b);

}  // namespace sfm::testing
