#include "backend/bundle_adjustment/observability.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sfm {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// The largest angle between two of the vectors (none zero), as lines (sign ignored) when `as_lines`.
double LargestAngleDeg(const std::vector<Eigen::Vector3d>& vectors, bool as_lines) {
  double largest = 0;
  for (size_t a = 0; a < vectors.size(); ++a) {
    for (size_t b = a + 1; b < vectors.size(); ++b) {
      const double cosine = vectors[a].dot(vectors[b]);
      const double angle =
          std::atan2(vectors[a].cross(vectors[b]).norm(), as_lines ? std::abs(cosine) : cosine);
      largest = std::max(largest, angle);
    }
  }
  return largest * kRadToDeg;
}

}  // namespace

double SmallestDepth(const std::vector<Eigen::Vector3d>& points, const std::vector<Pose3>& world_T_camera) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Pose3& pose : world_T_camera) {
    const Pose3 camera_T_world = pose.Inverse();
    for (const Eigen::Vector3d& point : points) smallest = std::min(smallest, (camera_T_world * point).z());
  }
  return smallest;
}

double ObservedLineDepth(const Eigen::Matrix3d& K, const Pose3& world_T_camera, const Eigen::Vector2d& p0,
                         const Eigen::Vector2d& p1, const Eigen::Vector3d& point,
                         const Eigen::Vector3d& direction) {
  const Eigen::Vector3d d = direction.normalized();
  const Eigen::Vector3d w = world_T_camera.translation - point;
  const Pose3 camera_T_world = world_T_camera.Inverse();
  const Eigen::Matrix3d K_inverse = K.inverse();
  double smallest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d* pixel : {&p0, &p1}) {
    // Closest points of the ray and the line: s along the line from `point`.
    const Eigen::Vector3d ray = (world_T_camera.rotation * (K_inverse * pixel->homogeneous())).normalized();
    const double cos_angle = ray.dot(d);
    const double sin_squared = 1 - cos_angle * cos_angle;
    if (!(sin_squared > 1e-18)) continue;
    const double s = (d.dot(w) - cos_angle * ray.dot(w)) / sin_squared;
    smallest = std::min(smallest, (camera_T_world * (point + s * d)).z());
  }
  return smallest;
}

double PointTriangulationAngleDeg(const Eigen::Vector3d& point,
                                  const std::vector<Eigen::Vector3d>& camera_centres) {
  std::vector<Eigen::Vector3d> rays;
  for (const Eigen::Vector3d& centre : camera_centres) {
    if (centre != point) rays.push_back(centre - point);
  }
  return LargestAngleDeg(rays, /*as_lines=*/false);
}

double LargestPlaneAngleDeg(const std::vector<Eigen::Vector3d>& plane_normals) {
  std::vector<Eigen::Vector3d> normals;
  for (const Eigen::Vector3d& normal : plane_normals) {
    if (normal.norm() > 0) normals.push_back(normal);
  }
  return LargestAngleDeg(normals, /*as_lines=*/true);
}

double LineTriangulationAngleDeg(const Eigen::Vector3d& point, const Eigen::Vector3d& direction,
                                 const std::vector<Eigen::Vector3d>& camera_centres) {
  const Eigen::Vector3d d = direction.normalized();
  std::vector<Eigen::Vector3d> normals;
  for (const Eigen::Vector3d& centre : camera_centres) {
    const Eigen::Vector3d normal = d.cross(centre - point);
    // A centre on the line (to 1e-12 of its distance from `point`) spans no plane with it.
    if (normal.norm() > 1e-12 * (centre - point).norm()) normals.push_back(normal);
  }
  return LargestPlaneAngleDeg(normals);
}

Eigen::Vector3d BackProjectedPlaneNormal(const Eigen::Matrix3d& K, const Eigen::Matrix3d& world_R_camera,
                                         const Eigen::Vector2d& p0, const Eigen::Vector2d& p1) {
  return world_R_camera * (K.transpose() * p0.homogeneous().cross(p1.homogeneous()));
}

}  // namespace sfm
