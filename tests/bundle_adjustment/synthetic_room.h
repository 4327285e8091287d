// Synthetic bundle-adjustment problems: a box room with framed rectangles on its walls, a robot
// with a camera on its base, exact projections plus Gaussian pixel noise, odometry made from the
// true motion with a scale error and a heading drift, and landmarks triangulated from the
// odometry poses (as the pipeline's triangulation would).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "backend/triangulation/landmarks.h"
#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"

namespace sfm::testing {

struct Scene {
  struct Segment {
    Eigen::Vector3d a, b;
    int point_at_a = -1;  // index into points of the junction at a, or -1
  };
  std::vector<Eigen::Vector3d> points;  // metres, world frame
  std::vector<Segment> segments;
};

// An 8 x 6 x 3 m room (x east, y north, z up, floor at z = 0): its 8 corners and 12 edges, and two
// framed rectangles on each wall (4 corners and 4 edges each): 40 points, 44 segments.
Scene BoxRoom();

// BoxRoom with four rugs on its floor (rectangles of 0.6 x 1.5 m between the loop of
// LoopTrajectory and each wall: 16 more points and segments at z = 0), for the floor prior; then
// everything moved up by floor_z (m): a floor away from the base origin's z = 0.
Scene BoxRoomWithRugs(double floor_z = 0);

// The generator's rig: 640 x 480, fx = fy = 450 px, principal point at the image centre; camera
// z = base x, camera x = -base y, camera y = -base z, 0.2 m ahead of the base origin and
// `height` m above the floor (0 for a camera on the base's vertical axis at the floor).
Calibration RobotCalibration(double forward = 0.2, double height = 1.0);

// world_T_base for `frames` poses evenly spaced in angle on one counter-clockwise lap of an
// ellipse centred in the room (semi-axes 2.2 m along x, 1.3 m along y), heading along the path.
std::vector<Pose3> LoopTrajectory(int frames);

// world_T_base for `frames` poses from `start` along +x, `step` m apart, heading +x.
std::vector<Pose3> StraightTrajectory(int frames, const Eigen::Vector2d& start, double step);

// Wheel odometry from the true poses: every step's translation scaled by (1 + scale_error), its
// rotation preceded by a yaw of heading_drift_rad + heading_noise_rad * N(0, 1); integrated from
// the true first pose.
std::vector<Pose3> MakeOdometry(const std::vector<Pose3>& world_T_base_true, double scale_error,
                                double heading_drift_rad, double heading_noise_rad, std::uint32_t seed);

struct Observed {
  Landmarks landmarks;                        // triangulated from the odometry poses
  std::vector<Eigen::Vector3d> true_points;   // per point landmark
  std::vector<Scene::Segment> true_segments;  // per line landmark
};

// Observations of the scene from the true poses (projections in front of the camera and inside
// the image, segments clipped to the image and kept when at least 30 px long; pixel noise
// N(0, pixel_noise_px) per coordinate), kept for landmarks seen in at least two frames, then
// triangulated from `world_T_base_odometry`: points by the linear method of Hartley & Zisserman
// section 12.2, lines as the least-squares intersection of their back-projected planes.
Observed Observe(const Scene& scene, const Calibration& calibration,
                 const std::vector<Pose3>& world_T_base_true, const std::vector<Pose3>& world_T_base_odometry,
                 double pixel_noise_px, std::uint32_t seed);

// World_T_camera positions for world_T_base poses.
std::vector<Eigen::Vector3d> CameraPositions(const std::vector<Pose3>& world_T_base,
                                             const Pose3& base_T_camera);

// RMS of |estimated_i - truth_i| (metres), no alignment.
double PositionRmse(const std::vector<Eigen::Vector3d>& estimated, const std::vector<Eigen::Vector3d>& truth);

// The same after the best scaling of the estimated positions about the first one (which the gauge
// holds on the truth): what is left once the scale error, which monocular vision cannot see, is
// taken out. `scale` (optional) receives the factor applied to the estimate.
double PositionRmseAfterScaling(const std::vector<Eigen::Vector3d>& estimated,
                                const std::vector<Eigen::Vector3d>& truth, double* scale);

// RMS over consecutive frames of the angle of (truth_i^-1 truth_{i+1})^-1 (est_i^-1 est_{i+1}),
// radians (Sturm et al. 2012's rotational RPE with a step of one frame).
double RotationRpe(const std::vector<Pose3>& estimated, const std::vector<Pose3>& truth);

}  // namespace sfm::testing
