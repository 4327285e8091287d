#include "sequences/generator/visibility.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sequences/generator/camera_rig.h"
#include "sequences/generator/renderer.h"
#include "sequences/generator/wireframe.h"

namespace sfm {
namespace {

// A 4 x 4 x 2.5 m room, a poster on its far wall (x = 4) and a box in front of the poster.
Scene PosterBehindBox() {
  Scene scene;
  const double h = 2.5;
  const Eigen::Vector3d b[4] = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  const Eigen::Vector3d t[4] = {{0, 0, h}, {4, 0, h}, {4, 4, h}, {0, 4, h}};
  const Eigen::Vector3d centre(2, 2, 1.25);
  scene.AddPolygon(scene.AddObject("floor"), {b[0], b[1], b[2], b[3]}, 0.4, Eigen::Vector3d::UnitZ());
  scene.AddPolygon(scene.AddObject("ceiling"), {t[0], t[1], t[2], t[3]}, 0.9, -Eigen::Vector3d::UnitZ());
  for (int i = 0; i < 4; ++i) {
    scene.AddPolygon(scene.AddObject("wall"), {b[i], b[(i + 1) % 4], t[(i + 1) % 4], t[i]}, 0.75,
                     centre - 0.5 * (b[i] + t[(i + 1) % 4]));
  }
  const double x = 4 - 0.005;
  scene.AddPolygon(scene.AddObject("poster"), {{x, 1.2, 0.3}, {x, 2.8, 0.3}, {x, 2.8, 1.2}, {x, 1.2, 1.2}}, 0.2,
                   -Eigen::Vector3d::UnitX());
  scene.AddBox(scene.AddObject("box", true), {2.5, 2}, 0, 0, {0.6, 0.6, 0.8}, 0.3, false);
  scene.floor_max = {4, 4};
  scene.ceiling_height = h;
  return scene;
}

int FindEdge(const Wireframe& wireframe, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  for (size_t e = 0; e < wireframe.edges.size(); ++e) {
    const Eigen::Vector3d& p = wireframe.vertices[wireframe.edges[e].vertex_a];
    const Eigen::Vector3d& q = wireframe.vertices[wireframe.edges[e].vertex_b];
    if (((p - a).norm() < 1e-9 && (q - b).norm() < 1e-9) || ((p - b).norm() < 1e-9 && (q - a).norm() < 1e-9)) {
      return static_cast<int>(e);
    }
  }
  return -1;
}

int FindVertex(const Wireframe& wireframe, const Eigen::Vector3d& p) {
  for (size_t v = 0; v < wireframe.vertices.size(); ++v) {
    if ((wireframe.vertices[v] - p).norm() < 1e-9) return static_cast<int>(v);
  }
  return -1;
}

struct View {
  Camera camera;
  Pose3 world_T_camera;
};

FrameTruth See(const Scene& scene, const Wireframe& wireframe, const View& view) {
  const Renderer renderer(scene, view.camera, RenderOptions());
  Canvas canvas;
  renderer.Rasterise(view.world_T_camera, &canvas);
  FrameTruth truth;
  ComputeFrameTruth(scene, wireframe, view.camera, view.world_T_camera, canvas, VisibilityOptions(), &truth);
  return truth;
}

// Camera 1 m high at (0.8, 2), looking along +x, unpitched.
View LookAlongX() {
  CameraRigOptions rig;
  rig.width = 320;
  rig.height = 240;
  rig.fx = rig.fy = 224;
  rig.pitch = 0;
  rig.mount_forward = 0;
  return {rig.MakeCamera(), Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.8, 2, 0)) * rig.BaseTCamera()};
}

TEST(VisibilityTest, BoxSplitsThePosterEdgeBehindIt) {
  const Scene scene = PosterBehindBox();
  const Wireframe wireframe = ExtractWireframe(scene);
  const View view = LookAlongX();
  const FrameTruth truth = See(scene, wireframe, view);
  const int bottom = FindEdge(wireframe, {3.995, 1.2, 0.3}, {3.995, 2.8, 0.3});
  ASSERT_GE(bottom, 0);
  std::vector<VisibleSegment> parts;
  for (const VisibleSegment& s : truth.segments) {
    if (s.edge == bottom) parts.push_back(s);
  }
  ASSERT_EQ(parts.size(), 2u) << "the box should hide the middle of the poster's bottom edge";
  // Each part runs from a poster corner to the box's silhouette: the vertical front edges of the
  // box at y = 1.7 and 2.3, x = 2.2, which project to u = cx -+ 224 * 0.3 / 1.4.
  const double cx = view.camera.cx;
  for (const VisibleSegment& s : parts) {
    const int occluded_end = s.end[0] == SegmentEnd::kOcclusion ? 0 : 1;
    EXPECT_EQ(s.end[occluded_end], SegmentEnd::kOcclusion);
    EXPECT_EQ(s.end[1 - occluded_end], SegmentEnd::kVertex);
    // The part on the image's right (the poster's y = 1.2 end) meets the box edge at y = 1.7.
    const bool right = s.pixel[1 - occluded_end].x() > cx;
    const double silhouette = right ? cx + 224 * 0.3 / 1.4 : cx - 224 * 0.3 / 1.4;
    // Conservative by at most one canvas sample (1/3 px) on either side of the contour.
    EXPECT_NEAR(s.pixel[occluded_end].x(), silhouette, /*max_error_px=*/0.7);
  }
  // The poster's top edge, above the box, is seen whole.
  const int top = FindEdge(wireframe, {3.995, 1.2, 1.2}, {3.995, 2.8, 1.2});
  int top_parts = 0;
  for (const VisibleSegment& s : truth.segments) {
    if (s.edge != top) continue;
    ++top_parts;
    EXPECT_EQ(s.end[0], SegmentEnd::kVertex);
    EXPECT_EQ(s.end[1], SegmentEnd::kVertex);
    EXPECT_EQ(s.t[0], 0);
    EXPECT_EQ(s.t[1], 1);
  }
  EXPECT_EQ(top_parts, 1);
  // The poster's bottom corners are visible, the box's far bottom corners are not.
  auto visible = [&](const Eigen::Vector3d& p) {
    const int v = FindVertex(wireframe, p);
    for (const VisibleVertex& seen : truth.vertices) {
      if (seen.vertex == v) return true;
    }
    return false;
  };
  EXPECT_TRUE(visible({3.995, 1.2, 0.3}));
  EXPECT_TRUE(visible({3.995, 2.8, 0.3}));
  EXPECT_TRUE(visible({2.2, 1.7, 0.8}));  // the box's top corners: the camera is above it
  EXPECT_TRUE(visible({2.8, 1.7, 0.8}));
  EXPECT_FALSE(visible({2.8, 1.7, 0}));   // its back bottom corners are behind it
  EXPECT_FALSE(visible({2.2, 1.7, 0}));   // its front bottom corners are below the image

}

TEST(VisibilityTest, BoxCornersAreYAndArrowJunctions) {
  const Scene scene = PosterBehindBox();
  const Wireframe wireframe = ExtractWireframe(scene);
  // From (0.8, 0.8), 1.6 m high, looking down at the box's near corner (2.2, 1.7).
  CameraRigOptions rig;
  rig.width = 320;
  rig.height = 240;
  rig.fx = rig.fy = 224;
  rig.mount_forward = 0;
  rig.mount_height = 1.6;
  const Eigen::Vector2d to_box = Eigen::Vector2d(2.5, 2) - Eigen::Vector2d(0.8, 0.8);
  rig.pitch = std::atan2(1.6 - 0.4, to_box.norm());
  const double yaw = std::atan2(to_box.y(), to_box.x());
  const View view{rig.MakeCamera(), Pose3(Eigen::Matrix3d(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())),
                                          Eigen::Vector3d(0.8, 0.8, 0)) *
                                        rig.BaseTCamera()};
  const FrameTruth truth = See(scene, wireframe, view);
  auto find = [&](const Eigen::Vector3d& p) -> const VisibleVertex* {
    const int v = FindVertex(wireframe, p);
    for (const VisibleVertex& seen : truth.vertices) {
      if (seen.vertex == v) return &seen;
    }
    return nullptr;
  };
  const VisibleVertex* top = find({2.2, 1.7, 0.8});
  const VisibleVertex* bottom = find({2.2, 1.7, 0});
  ASSERT_NE(top, nullptr);
  ASSERT_NE(bottom, nullptr);
  EXPECT_EQ(top->degree, 3);
  EXPECT_EQ(top->type, "Y");
  EXPECT_EQ(bottom->degree, 3);
  EXPECT_EQ(bottom->type, "ARROW");
  EXPECT_EQ(find({2.8, 2.3, 0}), nullptr);  // behind the box
}

TEST(VisibilityTest, EverythingListedIsInTheImageAndOnItsEdge) {
  const Scene scene = PosterBehindBox();
  const Wireframe wireframe = ExtractWireframe(scene);
  View view = LookAlongX();
  view.camera.distortion = {-0.3, 0.1, 0.001, 0.0005, 0};
  const FrameTruth truth = See(scene, wireframe, view);
  ASSERT_GT(truth.vertices.size(), 8u);
  ASSERT_GT(truth.segments.size(), 12u);
  const Pose3 camera_T_world = view.world_T_camera.Inverse();
  auto inside = [&](const Eigen::Vector2d& p) {
    return p.x() >= -0.5 && p.y() >= -0.5 && p.x() <= view.camera.width - 0.5 && p.y() <= view.camera.height - 0.5;
  };
  for (const VisibleVertex& v : truth.vertices) {
    const Eigen::Vector3d pc = camera_T_world * wireframe.vertices[v.vertex];
    EXPECT_LT((v.pixel - view.camera.ProjectUndistorted(pc)).norm(), 1e-9);
    EXPECT_LT((v.pixel_distorted - view.camera.Project(pc)).norm(), 1e-9);
    EXPECT_NEAR(v.depth, pc.z(), 1e-12);
    EXPECT_TRUE(inside(v.pixel_distorted));
  }
  for (const VisibleSegment& s : truth.segments) {
    const WireEdge& edge = wireframe.edges[s.edge];
    const Eigen::Vector3d& a = wireframe.vertices[edge.vertex_a];
    const Eigen::Vector3d& b = wireframe.vertices[edge.vertex_b];
    EXPECT_LE(0, s.t[0]);
    EXPECT_LT(s.t[0], s.t[1]);
    EXPECT_LE(s.t[1], 1);
    for (int i = 0; i < 2; ++i) {
      const Eigen::Vector3d pc = camera_T_world * Eigen::Vector3d(a + s.t[i] * (b - a));
      EXPECT_LT((s.pixel[i] - view.camera.ProjectUndistorted(pc)).norm(), 1e-6);
      EXPECT_LT((s.pixel_distorted[i] - view.camera.Project(pc)).norm(), 1e-6);
      // Ends at the border lie on it (within the bisection's precision); others inside.
      EXPECT_TRUE(inside(s.pixel_distorted[i] * (1 - 1e-7) + 1e-7 * Eigen::Vector2d(160, 120)));
    }
  }
}

}  // namespace
}  // namespace sfm
