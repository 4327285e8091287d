#include "tests/test_scenes.h"

namespace sfm::testing {

Scene RoomShell(double length, double width, double height) {
  Scene scene;
  const Eigen::Vector3d b[4] = {{0, 0, 0}, {length, 0, 0}, {length, width, 0}, {0, width, 0}};
  const Eigen::Vector3d t[4] = {{0, 0, height}, {length, 0, height}, {length, width, height}, {0, width, height}};
  const Eigen::Vector3d centre(length / 2, width / 2, height / 2);
  scene.AddPolygon(scene.AddObject("floor"), {b[0], b[1], b[2], b[3]}, 0.35, Eigen::Vector3d::UnitZ());
  scene.AddPolygon(scene.AddObject("ceiling"), {t[0], t[1], t[2], t[3]}, 0.9, -Eigen::Vector3d::UnitZ());
  const double wall_albedo[4] = {0.7, 0.6, 0.75, 0.65};
  for (int i = 0; i < 4; ++i) {
    scene.AddPolygon(scene.AddObject("wall"), {b[i], b[(i + 1) % 4], t[(i + 1) % 4], t[i]}, wall_albedo[i],
                     centre - 0.5 * (b[i] + t[(i + 1) % 4]));
  }
  scene.floor_min = {0, 0};
  scene.floor_max = {length, width};
  scene.ceiling_height = height;
  return scene;
}

}  // namespace sfm::testing
