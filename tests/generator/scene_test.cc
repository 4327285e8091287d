#include "sequences/generator/scene.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sequences/generator/scene_builder.h"
#include "sequences/generator/trajectory.h"
#include "sequences/generator/wireframe.h"

namespace sfm {
namespace {

Scene Build(SceneType type, std::uint64_t seed) {
  SceneOptions options;
  options.type = type;
  Scene scene;
  const Status status = BuildScene(options, seed, &scene);
  EXPECT_TRUE(status.ok()) << status.message();
  return scene;
}

TEST(SceneTest, BoxHasSixOutwardFacesAndTwelveEdges) {
  Scene scene;
  const int box = scene.AddObject("box", true);
  scene.AddBox(box, {1, 2}, 0.3, 0.5, {0.4, 0.2, 0.3}, 0.5, /*with_bottom=*/true);
  ASSERT_EQ(scene.faces.size(), 6u);
  const Eigen::Vector3d centre(1, 2, 0.65);
  for (const Face& face : scene.faces) {
    EXPECT_NEAR(face.normal.norm(), 1.0, 1e-12);
    // Outward: the centre is behind every face.
    EXPECT_LT(face.normal.dot(centre - face.vertices[0]), 0);
  }
  const Wireframe wireframe = ExtractWireframe(scene);
  EXPECT_EQ(wireframe.vertices.size(), 8u);
  EXPECT_EQ(wireframe.edges.size(), 12u);
  for (const WireEdge& edge : wireframe.edges) EXPECT_GE(edge.face_b, 0);
  // Without its bottom face the box keeps its 12 edges: the bottom ones border one face each.
  Scene open;
  open.AddBox(open.AddObject("box"), {1, 2}, 0.3, 0, {0.4, 0.2, 0.3}, 0.5, /*with_bottom=*/false);
  EXPECT_EQ(ExtractWireframe(open).edges.size(), 12u);
}

TEST(SceneTest, CoplanarFacesOfOneLookShareNoEdge) {
  Scene scene;
  const int object = scene.AddObject("floor");
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  scene.AddPolygon(object, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0.5, up);
  scene.AddPolygon(object, {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}, 0.5, up);
  EXPECT_EQ(ExtractWireframe(scene).edges.size(), 6u);  // the shared side is no image edge
  scene.faces[1].albedo = 0.7;
  EXPECT_EQ(ExtractWireframe(scene).edges.size(), 7u);  // now it is
}

class BuiltSceneTest : public ::testing::TestWithParam<std::tuple<SceneType, int>> {};

TEST_P(BuiltSceneTest, FacesArePlanarConvexAndInsideTheShell) {
  const auto [type, seed] = GetParam();
  const Scene scene = Build(type, seed);
  ASSERT_GT(scene.faces.size(), 100u);
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const Face& face = scene.faces[f];
    ASSERT_GE(face.vertices.size(), 3u);
    EXPECT_NEAR(face.normal.norm(), 1.0, 1e-12);
    const size_t n = face.vertices.size();
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d& p = face.vertices[i];
      EXPECT_NEAR(face.normal.dot(p), face.Offset(), /*max_plane_distance_m=*/1e-9) << "face " << f;
      // Convex and counter-clockwise about the normal: every turn goes the same way.
      const Eigen::Vector3d turn = (face.vertices[(i + 1) % n] - p).cross(face.vertices[(i + 2) % n] - face.vertices[(i + 1) % n]);
      EXPECT_GT(turn.dot(face.normal), 0) << "face " << f;
      EXPECT_GE(p.x(), scene.floor_min.x() - 1e-9);
      EXPECT_LE(p.x(), scene.floor_max.x() + 1e-9);
      EXPECT_GE(p.y(), scene.floor_min.y() - 1e-9);
      EXPECT_LE(p.y(), scene.floor_max.y() + 1e-9);
      EXPECT_GE(p.z(), -1e-9);
      EXPECT_LE(p.z(), scene.ceiling_height + 1e-9);
    }
    EXPECT_GE(face.albedo, 0.0);
    EXPECT_LE(face.albedo, 1.0);
  }
}

TEST_P(BuiltSceneTest, EveryEdgeBetweenTwoFacesHasContrast) {
  const auto [type, seed] = GetParam();
  const Scene scene = Build(type, seed);
  const Wireframe wireframe = ExtractWireframe(scene);
  ASSERT_GT(wireframe.edges.size(), 200u);
  int two_faced = 0;
  for (const WireEdge& edge : wireframe.edges) {
    if (edge.face_b < 0) continue;
    ++two_faced;
    const double a = scene.lighting.Shade(scene.faces[edge.face_a]);
    const double b = scene.lighting.Shade(scene.faces[edge.face_b]);
    EXPECT_GE(std::abs(a - b), /*min_contrast=*/0.04 - 1e-12)
        << scene.objects[scene.faces[edge.face_a].object].kind << " / "
        << scene.objects[scene.faces[edge.face_b].object].kind << " faces " << edge.face_a << " ("
        << scene.faces[edge.face_a].normal.transpose() << ", albedo " << scene.faces[edge.face_a].albedo << ") and "
        << edge.face_b << " (" << scene.faces[edge.face_b].normal.transpose() << ", albedo "
        << scene.faces[edge.face_b].albedo << ")";
  }
  EXPECT_GT(two_faced, 100);
}

TEST_P(BuiltSceneTest, ObstaclesLeaveThePathsFree) {
  const auto [type, seed] = GetParam();
  const Scene scene = Build(type, seed);
  int obstacles = 0;
  for (const SceneObject& object : scene.objects) obstacles += object.obstacle;
  EXPECT_GT(obstacles, 4);
  // Straight and turns along the lane to the far end, and (room) the loop, keep robot_radius
  // clear of every obstacle and wall.
  std::vector<TrajectoryType> types = {TrajectoryType::kStraight, TrajectoryType::kTurns};
  if (type == SceneType::kRoom) types.push_back(TrajectoryType::kLoop);
  for (TrajectoryType trajectory : types) {
    TrajectoryOptions options;
    options.type = trajectory;
    options.num_frames = 0;
    std::vector<Pose3> poses;
    const Status status = MakeTrajectory(options, scene, &poses);
    EXPECT_TRUE(status.ok()) << TrajectoryTypeName(trajectory) << ": " << status.message();
    EXPECT_GT(poses.size(), 10u);
  }
}

TEST_P(BuiltSceneTest, SameSeedSameScene) {
  const auto [type, seed] = GetParam();
  const Scene a = Build(type, seed), b = Build(type, seed), c = Build(type, seed + 1);
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (size_t f = 0; f < a.faces.size(); ++f) {
    ASSERT_EQ(a.faces[f].vertices.size(), b.faces[f].vertices.size());
    for (size_t i = 0; i < a.faces[f].vertices.size(); ++i) EXPECT_EQ(a.faces[f].vertices[i], b.faces[f].vertices[i]);
    EXPECT_EQ(a.faces[f].albedo, b.faces[f].albedo);
  }
  EXPECT_TRUE(a.faces.size() != c.faces.size() || a.faces[10].vertices[0] != c.faces[10].vertices[0]);
}

INSTANTIATE_TEST_SUITE_P(Scenes, BuiltSceneTest,
                         ::testing::Combine(::testing::Values(SceneType::kCorridor, SceneType::kRoom),
                                            ::testing::Values(1, 2, 3, 4)));

// The sparse variant (SceneOptions::sparse, make_sequence --sparse): cabinets and doors only, far
// apart, so the scene keeps at most 40 % of the full scene's wireframe edges (seeds 1-4 measured
// 25-35 %), and still at least 60 edges besides the shell's 12 and one piece of furniture on the
// walls; its edges keep their contrast and the trajectories stay clear.
class SparseSceneTest : public ::testing::TestWithParam<std::tuple<SceneType, int>> {};

TEST_P(SparseSceneTest, FewObjectsBareWalls) {
  const auto [type, seed] = GetParam();
  SceneOptions options;
  options.type = type;
  options.sparse = true;
  Scene sparse;
  ASSERT_TRUE(BuildScene(options, seed, &sparse).ok());
  const size_t full_edges = ExtractWireframe(Build(type, seed)).edges.size();
  const Wireframe wireframe = ExtractWireframe(sparse);
  EXPECT_LE(wireframe.edges.size(), /*max_share_of_full=*/0.4 * full_edges);
  EXPECT_GE(wireframe.edges.size(), /*min_edges=*/60u);
  int furniture = 0;
  for (const SceneObject& object : sparse.objects) {
    EXPECT_TRUE(object.kind == "floor" || object.kind == "ceiling" || object.kind == "wall" ||
                object.kind == "ceiling_light" || object.kind == "cabinet" || object.kind == "cabinet_door" ||
                object.kind == "door_frame" || object.kind == "door")
        << object.kind;
    furniture += object.kind == "cabinet" || object.kind == "door_frame";
  }
  EXPECT_GE(furniture, type == SceneType::kCorridor ? 2 : 1);  // the corridor's end door and more
  for (const WireEdge& edge : wireframe.edges) {
    if (edge.face_b < 0) continue;
    EXPECT_GE(std::abs(sparse.lighting.Shade(sparse.faces[edge.face_a]) -
                       sparse.lighting.Shade(sparse.faces[edge.face_b])),
              /*min_contrast=*/0.04 - 1e-12);
  }
  std::vector<TrajectoryType> trajectories = {TrajectoryType::kStraight, TrajectoryType::kTurns};
  if (type == SceneType::kRoom) trajectories.push_back(TrajectoryType::kLoop);
  for (TrajectoryType trajectory : trajectories) {
    TrajectoryOptions trajectory_options;
    trajectory_options.type = trajectory;
    trajectory_options.num_frames = 0;
    std::vector<Pose3> poses;
    const Status status = MakeTrajectory(trajectory_options, sparse, &poses);
    EXPECT_TRUE(status.ok()) << TrajectoryTypeName(trajectory) << ": " << status.message();
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SparseSceneTest,
                         ::testing::Combine(::testing::Values(SceneType::kCorridor, SceneType::kRoom),
                                            ::testing::Values(1, 2, 3, 4)));

TEST(SceneOptionsTest, CheckRejectsBadValues) {
  SceneOptions options;
  EXPECT_TRUE(options.Check().ok());
  options.ceiling_height = 2.0;
  EXPECT_FALSE(options.Check().ok());
  options = SceneOptions();
  options.corridor_width = 1.0;
  EXPECT_FALSE(options.Check().ok());
  options = SceneOptions();
  options.corridor_length = 0;  // only GenerateSequence fits it
  Scene scene;
  EXPECT_FALSE(BuildScene(options, 1, &scene).ok());
}

}  // namespace
}  // namespace sfm
