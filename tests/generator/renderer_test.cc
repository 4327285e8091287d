#include "sequences/generator/renderer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "sequences/generator/camera_rig.h"
#include "sequences/generator/scene_builder.h"

namespace sfm {
namespace {

// A 4 x 4 x 2.5 m room (inward faces) and, when asked, a box in the middle of it.
void AddRoom(Scene* scene) {
  const double h = 2.5;
  const Eigen::Vector3d b[4] = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  const Eigen::Vector3d t[4] = {{0, 0, h}, {4, 0, h}, {4, 4, h}, {0, 4, h}};
  const Eigen::Vector3d centre(2, 2, 1.25);
  scene->AddPolygon(scene->AddObject("floor"), {b[0], b[1], b[2], b[3]}, 0.4, Eigen::Vector3d::UnitZ());
  scene->AddPolygon(scene->AddObject("ceiling"), {t[0], t[1], t[2], t[3]}, 0.9, -Eigen::Vector3d::UnitZ());
  for (int i = 0; i < 4; ++i) {
    scene->AddPolygon(scene->AddObject("wall"), {b[i], b[(i + 1) % 4], t[(i + 1) % 4], t[i]}, 0.75,
                      centre - 0.5 * (b[i] + t[(i + 1) % 4]));
  }
  scene->floor_min = {0, 0};
  scene->floor_max = {4, 4};
  scene->ceiling_height = h;
}
void AddCentreBox(Scene* scene) {
  // Off-centre so that its vertical edges do not fall on pixel borders.
  scene->AddBox(scene->AddObject("box", true), {2.5, 2.03}, 0, 0, {0.6, 0.6, 0.8}, 0.3, false);
}

Camera TestCamera(int width = 320, int height = 240) {
  CameraRigOptions rig;
  rig.width = width;
  rig.height = height;
  rig.fx = rig.fy = 0.7 * width;
  return rig.MakeCamera();
}

// Camera 1 m high at x = 0.8, looking along +x (no pitch).
Pose3 LookAlongX() {
  CameraRigOptions rig;
  rig.pitch = 0;
  rig.mount_forward = 0;
  return Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.8, 2, 0)) * rig.BaseTCamera();
}

RenderOptions Exact() {
  RenderOptions options;
  options.supersampling = 1;
  options.blur_sigma = 0;
  options.noise_sigma = 0;
  return options;
}

int GreyOf(const Scene& scene, int face) { return static_cast<int>(std::floor(255 * scene.lighting.Shade(scene.faces[face]) + 0.5)); }

TEST(RendererTest, NearestFaceWinsWhateverTheDrawingOrder) {
  Scene room_first, box_first;
  AddRoom(&room_first);
  AddCentreBox(&room_first);
  AddCentreBox(&box_first);
  AddRoom(&box_first);
  const Camera camera = TestCamera();
  const cv::Mat a = Renderer(room_first, camera, Exact()).Render(LookAlongX(), 1);
  const cv::Mat b = Renderer(box_first, camera, Exact()).Render(LookAlongX(), 1);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
  // The box's front face (normal -x) covers the image 60 px below the centre; the far wall shows
  // 40 px above it.
  const Eigen::Vector2d centre(camera.cx, camera.cy);
  int front = -1;
  for (size_t f = 0; f < room_first.faces.size(); ++f) {
    if (room_first.objects[room_first.faces[f].object].kind == "box" && room_first.faces[f].normal.x() < -0.99) front = f;
  }
  ASSERT_GE(front, 0);
  EXPECT_EQ(a.at<unsigned char>(static_cast<int>(centre.y()) + 60, static_cast<int>(centre.x())), GreyOf(room_first, front));
  int far_wall = -1;
  for (size_t f = 0; f < room_first.faces.size(); ++f) {
    if (room_first.objects[room_first.faces[f].object].kind == "wall" && room_first.faces[f].normal.x() < -0.99) far_wall = f;
  }
  ASSERT_GE(far_wall, 0);
  EXPECT_EQ(a.at<unsigned char>(static_cast<int>(centre.y()) - 40, static_cast<int>(centre.x())), GreyOf(room_first, far_wall));
}

TEST(RendererTest, SupersamplingAntiAliasesEdges) {
  Scene scene;
  AddRoom(&scene);
  AddCentreBox(&scene);
  RenderOptions options = Exact();
  options.supersampling = 4;
  const cv::Mat image = Renderer(scene, TestCamera(), options).Render(LookAlongX(), 1);
  // Along a row through the box, some pixels lie strictly between the box and the wall behind.
  const int row = 180;  // through the box's front face
  int between = 0;
  for (int x = 1; x + 1 < image.cols; ++x) {
    const int left = image.at<unsigned char>(row, x - 1), right = image.at<unsigned char>(row, x + 1);
    const int v = image.at<unsigned char>(row, x);
    if (std::abs(left - right) > 20 && v > std::min(left, right) + 2 && v < std::max(left, right) - 2) ++between;
  }
  EXPECT_GE(between, 2);
}

TEST(RendererTest, SameSeedSameBytesAndNoiseHasItsSigma) {
  SceneOptions scene_options;
  scene_options.corridor_length = 12;
  Scene scene;
  ASSERT_TRUE(BuildScene(scene_options, 5, &scene).ok());
  CameraRigOptions rig;
  const Camera camera = rig.MakeCamera();
  const Pose3 world_T_camera = Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0)) * rig.BaseTCamera();
  RenderOptions options;
  options.noise_sigma = 3.0;
  const Renderer renderer(scene, camera, options);
  const cv::Mat a = renderer.Render(world_T_camera, 11), b = renderer.Render(world_T_camera, 11);
  const cv::Mat c = renderer.Render(world_T_camera, 12);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
  cv::Mat difference;
  cv::subtract(a, c, difference, cv::noArray(), CV_64F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(difference, mean, stddev);
  // Two independent noises of sigma 3, each rounded: sqrt(2 * (9 + 1/12)) = 4.26 grey levels.
  EXPECT_NEAR(mean[0], 0.0, 0.05);
  EXPECT_NEAR(stddev[0], 4.26, /*max_sigma_error=*/0.15);
}

TEST(RendererTest, DistortedImageIsFullyCovered) {
  Scene scene;
  AddRoom(&scene);
  AddCentreBox(&scene);
  Camera camera = TestCamera();
  camera.distortion = {-0.35, 0.12, 0.001, -0.001, -0.01};
  const cv::Mat image = Renderer(scene, camera, Exact()).Render(LookAlongX(), 1);
  double min_value = 0;
  cv::minMaxLoc(image, &min_value);
  EXPECT_GT(min_value, 0) << "a pixel saw no face: the canvas does not cover the distorted image";
  // The pixel where the box's top-front-left corner projects (distorted) sits at a corner of the
  // box's image: box on one side, wall on the other.
  const Eigen::Vector3d corner_world(2.2, 2.33, 0.8);
  const Pose3 camera_T_world = LookAlongX().Inverse();
  const Eigen::Vector2d p = camera.Project(camera_T_world * corner_world);
  const int x = static_cast<int>(std::lround(p.x())), y = static_cast<int>(std::lround(p.y()));
  const int inside = image.at<unsigned char>(y + 3, x + 3), outside = image.at<unsigned char>(y - 3, x - 3);
  EXPECT_GT(std::abs(inside - outside), 10) << "no edge at the distorted corner (" << x << ", " << y << ")";
}

TEST(RenderOptionsTest, CheckRejectsBadValues) {
  RenderOptions options;
  EXPECT_TRUE(options.Check().ok());
  options.supersampling = 0;
  EXPECT_FALSE(options.Check().ok());
  options = RenderOptions();
  options.noise_sigma = -1;
  EXPECT_FALSE(options.Check().ok());
}

}  // namespace
}  // namespace sfm
