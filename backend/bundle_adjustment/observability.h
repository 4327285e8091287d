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

namespace sfm {

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
