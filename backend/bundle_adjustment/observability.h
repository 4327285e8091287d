// Whether a landmark's position is determined by the views it has: the triangulation angle of a
// point (Hartley & Zisserman 2003, section 12.6: depth is unobservable without parallax), and its
// counterpart for a line (Bartoli & Sturm 2005: a line is recovered as the intersection of the
// planes through each camera centre and its image line; when those planes coincide - the line
// parallel to the motion, or in an epipolar plane of every view pair - its position within that
// plane is free).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "geometry/pose.h"

namespace sfm {

// The smallest depth (z in the camera frame, metres) of any of `points` in any of the cameras;
// +infinity with no point or no camera. A landmark too close to a camera that sees it is as
// undetermined as one without parallax: with (nearly) coincident centres, its triangulation lands
// next to them, where the triangulation angles below are large.
double SmallestDepth(const std::vector<Eigen::Vector3d>& points, const std::vector<Pose3>& world_T_camera);

// The smaller depth (z in the camera frame, metres) of the points of the line (`point`,
// `direction`) that the camera sees at the undistorted pixels p0 and p1: each the point of the
// line nearest to the pixel's viewing ray (a ray within 1e-9 rad of parallel to the line is
// skipped; +infinity when both are). The part of the line the view observes, not the stored
// segment's ends, which other views may extend behind this camera.
double ObservedLineDepth(const Eigen::Matrix3d& K, const Pose3& world_T_camera, const Eigen::Vector2d& p0,
                         const Eigen::Vector2d& p1, const Eigen::Vector3d& point,
                         const Eigen::Vector3d& direction);

// The largest angle between the viewing rays of two camera centres onto `point` (degrees,
// [0, 180]); 0 with fewer than two centres. A centre at the point contributes no ray.
double PointTriangulationAngleDeg(const Eigen::Vector3d& point,
                                  const std::vector<Eigen::Vector3d>& camera_centres);

// The largest angle between two of the planes with the given normals (degrees, [0, 90]; sign
// ignored); 0 with fewer than two. Zero normals are skipped.
double LargestPlaneAngleDeg(const std::vector<Eigen::Vector3d>& plane_normals);

// The largest angle between the planes through the line (`point`, `direction`) and two camera
// centres (degrees, [0, 90]); 0 with fewer than two centres. A centre on the line contributes no
// plane. Depends on the line's estimate, which a degenerate triangulation leaves arbitrary: see
// BackProjectedPlaneNormal for the measured counterpart.
double LineTriangulationAngleDeg(const Eigen::Vector3d& point, const Eigen::Vector3d& direction,
                                 const std::vector<Eigen::Vector3d>& camera_centres);

// The world-frame normal of the plane through the camera centre and the image line through the
// undistorted pixels p0 and p1: R K^T (p0 x p1) in homogeneous pixels (Hartley & Zisserman 2003,
// result 8.2: the back-projection of a line l is P^T l), R = world_R_camera.
Eigen::Vector3d BackProjectedPlaneNormal(const Eigen::Matrix3d& K, const Eigen::Matrix3d& world_R_camera,
                                         const Eigen::Vector2d& p0, const Eigen::Vector2d& p1);

}  // namespace sfm
