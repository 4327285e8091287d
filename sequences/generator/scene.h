// Scene: what the synthetic generator renders. A scene is a set of planar convex polygons, each
// with an albedo, grouped into objects (a wall, a cabinet, a poster...). World frame: z up, the
// floor is z = 0, lengths in metres.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sfm {

struct Face {
  std::vector<Eigen::Vector3d> vertices;            // convex, planar, counter-clockwise seen from the normal's side
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, pointing to the side the face is seen from
  double albedo = 0.5;                              // reflectance in [0, 1]
  double emission = 0;                              // emitted brightness in [0, 1] (ceiling lights)
  int object = -1;                                  // index into Scene::objects

  // Signed distance of the face's plane from the origin along the normal: normal . x = Offset().
  double Offset() const { return normal.dot(vertices.front()); }
};

struct SceneObject {
  std::string kind;                 // "floor", "wall", "cabinet", "shelf", "poster", ...
  Eigen::AlignedBox2d footprint;    // x-y extent in the world (empty for wall-mounted flat things)
  bool obstacle = false;            // stands on the floor: the robot must keep clear of it
};

// Brightness of a face in [0, 1] under the scene's light: albedo * (ambient + diffuse * |n . l|)
// plus the face's emission, clamped to 1. Lambertian with a two-sided directional light, so it
// does not depend on the viewpoint.
struct Lighting {
  Eigen::Vector3d direction = Eigen::Vector3d(0.30, 0.55, 0.78).normalized();  // towards the light, unit
  double ambient = 0.3;                                                        // [0, 1]
  double diffuse = 0.7;                                                        // [0, 1]

  double Shade(const Eigen::Vector3d& normal, double albedo, double emission = 0) const;
  double Shade(const Face& face) const { return Shade(face.normal, face.albedo, face.emission); }
};

struct Scene {
  std::vector<Face> faces;
  std::vector<SceneObject> objects;
  Eigen::Vector2d floor_min = Eigen::Vector2d::Zero();  // the floor is the rectangle floor_min..floor_max
  Eigen::Vector2d floor_max = Eigen::Vector2d::Zero();
  double ceiling_height = 0;                            // m
  Lighting lighting;       // the light the scene is rendered under
  double lane_y = 0;  // y of the free lane along x that straight and turning trajectories follow, m

  int AddObject(const std::string& kind, bool obstacle = false);

  // Adds a convex planar polygon to `object`. The vertex order is reversed if needed so that the
  // normal (Newell's method) points along `facing` (any vector on the visible side). CHECKs that
  // the polygon has at least 3 vertices and a non-zero area.
  void AddPolygon(int object, std::vector<Eigen::Vector3d> vertices, double albedo,
                  const Eigen::Vector3d& facing, double emission = 0);

  // Adds an upright box: base centre `centre_xy`, rotated by `yaw` (rad) about z, bottom at
  // `z_min`, extent `size` = (length along its rotated x, depth along its rotated y, height).
  // Faces point outwards. The bottom face is left out when `with_bottom` is false (a box standing
  // on the floor). Also grows the object's footprint.
  void AddBox(int object, const Eigen::Vector2d& centre_xy, double yaw, double z_min,
              const Eigen::Vector3d& size, double albedo, bool with_bottom);
};


}  // namespace sfm
