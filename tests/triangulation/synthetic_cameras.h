// Cameras around a known scene for the triangulation tests: poses that look at a target, exact
// projection, and seeded pixel noise.
#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

#include "geometry/pose.h"

namespace sfm::testing {

// The generator's camera: 640 x 480, fx = fy = 450, principal point at the image centre.
Eigen::Matrix3d TestK();

// world_T_camera of a camera at `centre` looking at `target`, image x right and y down with the
// world's z up (OpenCV camera frame: z forward).
Pose3 LookAt(const Eigen::Vector3d& centre, const Eigen::Vector3d& target);

// Five cameras of a robot driving 1.6 m along x (0.4 m apart) at 1 m height, looking ahead.
std::vector<Pose3> ForwardCameras();

// Undistorted pixel of a world point, K (R X + t) dehomogenised; also for a point behind the camera.
Eigen::Vector2d Project(const Eigen::Matrix3d& K, const Pose3& world_T_camera, const Eigen::Vector3d& point);

// Pixel noise: independent Gaussian x and y, sigma in pixels.
Eigen::Vector2d PixelNoise(std::mt19937& random, double sigma_px);

// Angle between two lines' directions, radians in [0, pi/2] (signs ignored).
double LineAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// Distance of a point from the line through `point` along unit `direction`.
double DistanceToLine(const Eigen::Vector3d& x, const Eigen::Vector3d& point,
                      const Eigen::Vector3d& direction);

}  // namespace sfm::testing
