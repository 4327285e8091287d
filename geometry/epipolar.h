// Epipolar geometry from calibration and odometry (paper eq. 7): x2^T F x1 = 0 for pixels of the
// undistorted images of frame 1 and frame 2.
#pragma once

#include <Eigen/Core>

#include "geometry/camera.h"
#include "geometry/pose.h"

namespace sfm {

// F from the camera poses: x2^T F x1 = 0, with x1 in camera 1 and x2 in camera 2 (undistorted pixels).
Eigen::Matrix3d FundamentalFromPoses(const Eigen::Matrix3d& K, const Pose3& world_T_camera1,
                                     const Pose3& world_T_camera2);

// F from two odometry poses of the robot base and the camera's mounting on it.
Eigen::Matrix3d FundamentalFromOdometry(const Eigen::Matrix3d& K, const Pose3& base_T_camera,
                                        const Pose3& world_T_base1, const Pose3& world_T_base2);

// F from two 3x4 projection matrices (x ~ P X), as for the VGG data: F = [e2]x P2 P1^+.
Eigen::Matrix3d FundamentalFromProjections(const Eigen::Matrix<double, 3, 4>& P1,
                                           const Eigen::Matrix<double, 3, 4>& P2);

// Epipolar line in image 2 of pixel p1 of image 1: l2 = F [p1; 1] (not normalised).
Eigen::Vector3d EpipolarLineInImage2(const Eigen::Matrix3d& F, const Eigen::Vector2d& p1);
// Epipolar line in image 1 of pixel p2 of image 2: l1 = F^T [p2; 1].
Eigen::Vector3d EpipolarLineInImage1(const Eigen::Matrix3d& F, const Eigen::Vector2d& p2);

// Perpendicular distance in pixels from p to the line l = (a, b, c), a x + b y + c = 0.
// Returns +infinity for a degenerate line (a = b = 0).
double PointLineDistance(const Eigen::Vector3d& line, const Eigen::Vector2d& p);

// Symmetric epipolar distance: mean of the distances of p2 to l2(p1) and of p1 to l1(p2).
double SymmetricEpipolarDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& p1,
                                 const Eigen::Vector2d& p2);

}  // namespace sfm
