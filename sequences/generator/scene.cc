#include "sequences/generator/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <glog/logging.h>

namespace sfm {

int Scene::AddObject(const std::string& kind, bool obstacle) {
  SceneObject object;
  object.kind = kind;
  object.obstacle = obstacle;
  objects.push_back(object);
  return static_cast<int>(objects.size()) - 1;
}

void Scene::AddPolygon(int object, std::vector<Eigen::Vector3d> vertices, double albedo,
                       const Eigen::Vector3d& facing, double emission) {
  CHECK_GE(object, 0);
  CHECK_LT(object, static_cast<int>(objects.size()));
  CHECK_GE(vertices.size(), 3u);
  // Newell's method: robust normal of a planar polygon.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < vertices.size(); ++i) {
    normal += vertices[i].cross(vertices[(i + 1) % vertices.size()]);
  }
  CHECK_GT(normal.norm(), 1e-12) << "degenerate polygon";
  normal.normalize();
  if (normal.dot(facing) < 0) {
    std::reverse(vertices.begin(), vertices.end());
    normal = -normal;
  }
  Face face;
  face.vertices = std::move(vertices);
  face.normal = normal;
  face.albedo = albedo;
  face.emission = emission;
  face.object = object;
  faces.push_back(std::move(face));
}

void Scene::AddBox(int object, const Eigen::Vector2d& centre_xy, double yaw, double z_min,
                   const Eigen::Vector3d& size, double albedo, bool with_bottom) {
  CHECK_GT(size.minCoeff(), 0);
  const Eigen::Vector2d ax(std::cos(yaw), std::sin(yaw));
  const Eigen::Vector2d ay(-ax.y(), ax.x());
  const double z_max = z_min + size.z();
  // Corners 0..3 counter-clockwise seen from above; each corner is computed once so that faces
  // sharing an edge share its end-points exactly.
  std::array<Eigen::Vector2d, 4> xy;
  const double sx[4] = {-0.5, 0.5, 0.5, -0.5};
  const double sy[4] = {-0.5, -0.5, 0.5, 0.5};
  for (int i = 0; i < 4; ++i) xy[i] = centre_xy + sx[i] * size.x() * ax + sy[i] * size.y() * ay;
  std::array<Eigen::Vector3d, 4> bottom, top;
  for (int i = 0; i < 4; ++i) {
    bottom[i] = Eigen::Vector3d(xy[i].x(), xy[i].y(), z_min);
    top[i] = Eigen::Vector3d(xy[i].x(), xy[i].y(), z_max);
  }
  const Eigen::Vector3d centre(centre_xy.x(), centre_xy.y(), 0.5 * (z_min + z_max));
  AddPolygon(object, {top[0], top[1], top[2], top[3]}, albedo, Eigen::Vector3d::UnitZ());
  if (with_bottom) AddPolygon(object, {bottom[3], bottom[2], bottom[1], bottom[0]}, albedo, -Eigen::Vector3d::UnitZ());
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    const Eigen::Vector3d side_centre = 0.5 * (bottom[i] + top[j]);
    AddPolygon(object, {bottom[i], bottom[j], top[j], top[i]}, albedo, side_centre - centre);
  }
  Eigen::AlignedBox2d& footprint = objects[object].footprint;
  for (const Eigen::Vector2d& corner : xy) footprint.extend(corner);
}

double Lighting::Shade(const Eigen::Vector3d& normal, double albedo, double emission) const {
  const double light = ambient + diffuse * std::abs(normal.dot(direction));
  return std::min(1.0, albedo * light + emission);
}

}  // namespace sfm
