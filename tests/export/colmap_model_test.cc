#include "backend/export/colmap_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "tests/test_data.h"

namespace sfm {
namespace {

using testing::ReadFile;

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void ExpectSameLines(const std::string& path, const std::string& expected) {
  const std::vector<std::string> actual_lines = Lines(ReadFile(path));
  const std::vector<std::string> expected_lines = Lines(expected);
  ASSERT_EQ(actual_lines.size(), expected_lines.size()) << path << ":\n" << ReadFile(path);
  for (size_t i = 0; i < expected_lines.size(); ++i) {
    EXPECT_EQ(actual_lines[i], expected_lines[i]) << path << " line " << i + 1;
  }
  EXPECT_EQ(ReadFile(path), expected);  // and nothing between or after the lines
}

Camera TestCamera() {
  Camera camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = 500;
  camera.fy = 510;
  camera.cx = 319.5;
  camera.cy = 239.5;
  return camera;
}

// Three cameras chosen so that every number in the files is exact:
//   image 0: identity rotation at c = (1, 2, 3), so camera_T_world has t = -c;
//   image 1: turned 180 degrees about x (looking down) at (0, 0, 10);
//   image 2: turned 90 degrees about z at the origin, seeing nothing (an empty points line).
// Points: P1 = (1, 2, 5) seen by images 1 and 0 (listed in that order, the image-0 observation
// 3, 4 px off: error (0 + 5) / 2); P2 = (0, 0, 6) seen by image 1 exactly; P3 = (1, 2, 1) behind
// camera 0 (error -1).
ColmapModel TinyModel() {
  ColmapModel model;
  model.camera = TestCamera();
  const double s = std::sqrt(0.5);
  model.images = {
      {"images/000000.png", Pose3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1, 2, 3))},
      {"images/000001.png", Pose3(Eigen::Quaterniond(0, 1, 0, 0), Eigen::Vector3d(0, 0, 10))},
      {"images/000002.png", Pose3(Eigen::Quaterniond(s, 0, 0, s), Eigen::Vector3d(0, 0, 0))},
  };
  model.points = {
      {{1, 2, 5}, {{1, {419.5, 35.5}}, {0, {322.5, 243.5}}}},
      {{0, 0, 6}, {{1, {319.5, 239.5}}}},
      {{1, 2, 1}, {{0, {100, 100}}}},
  };
  return model;
}

TEST(ColmapModelTest, WritesTheHandComputedTinyModel) {
  const std::string dir = testing::MakeScratchDir("colmap_tiny") + "/colmap";  // created by the writer
  const Status written = WriteColmapModel(dir, TinyModel());
  ASSERT_TRUE(written.ok()) << written.message();

  // cx, cy shifted by +0.5: COLMAP puts the centre of the top-left pixel at (0.5, 0.5).
  ExpectSameLines(dir + "/cameras.txt",
                  "# Camera list with one line of data per camera:\n"
                  "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
                  "# Number of cameras: 1\n"
                  "1 PINHOLE 640 480 500 510 320 240\n");
  // camera_T_world, QW first; the 90-degree turn about z is stored as its inverse (QZ < 0).
  ExpectSameLines(dir + "/images.txt",
                  "# Image list with two lines of data per image:\n"
                  "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
                  "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
                  "# Number of images: 3, mean observations per image: 1.3333333333333333\n"
                  "1 1 0 0 0 -1 -2 -3 1 images/000000.png\n"
                  "323 244 1 100.5 100.5 3\n"
                  "2 0 -1 0 0 0 0 10 1 images/000001.png\n"
                  "420 36 1 320 240 2\n"
                  "3 0.7071067811865476 0 0 -0.7071067811865476 0 0 0 1 images/000002.png\n"
                  "\n");
  // TRACK pairs are (IMAGE_ID, POINT2D_IDX): P1 is 2D point 0 of image 2 and 2D point 0 of image 1.
  ExpectSameLines(dir + "/points3D.txt",
                  "# 3D point list with one line of data per point:\n"
                  "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
                  "# Number of points: 3, mean track length: 1.3333333333333333\n"
                  "1 1 2 5 128 128 128 2.5 2 0 1 0\n"
                  "2 0 0 6 128 128 128 0 2 1\n"
                  "3 1 2 1 128 128 128 -1 1 1\n");
}

// The files parsed back as COLMAP would read them.
struct ParsedModel {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  struct Image {
    Eigen::Quaterniond camera_from_world;
    Eigen::Vector3d translation;
    std::vector<std::pair<Eigen::Vector2d, long>> points2d;  // (x, y), POINT3D_ID
  };
  std::map<long, Image> images;
  struct Point {
    Eigen::Vector3d xyz;
    double error = 0;
    std::vector<std::pair<long, size_t>> track;  // IMAGE_ID, POINT2D_IDX
  };
  std::map<long, Point> points;
};

// The lines that are not '#' comments.
std::vector<std::string> DataLines(const std::string& path) {
  std::vector<std::string> lines;
  for (const std::string& line : Lines(ReadFile(path))) {
    if (line.empty() || line[0] != '#') lines.push_back(line);
  }
  return lines;
}

ParsedModel Parse(const std::string& dir) {
  ParsedModel parsed;
  std::istringstream camera(DataLines(dir + "/cameras.txt").at(0));
  std::string model_name;
  int id = 0, width = 0, height = 0;
  camera >> id >> model_name >> width >> height >> parsed.fx >> parsed.fy >> parsed.cx >> parsed.cy;
  // Two lines per image; the second is empty for an image without observations.
  const std::vector<std::string> image_lines = DataLines(dir + "/images.txt");
  for (size_t i = 0; i + 1 < image_lines.size(); i += 2) {
    std::istringstream pose(image_lines[i]);
    long image_id = 0;
    double qw, qx, qy, qz;
    ParsedModel::Image image;
    pose >> image_id >> qw >> qx >> qy >> qz >> image.translation.x() >> image.translation.y() >>
        image.translation.z();
    image.camera_from_world = Eigen::Quaterniond(qw, qx, qy, qz);
    std::istringstream points(image_lines[i + 1]);
    double x, y;
    long point_id;
    while (points >> x >> y >> point_id) image.points2d.push_back({Eigen::Vector2d(x, y), point_id});
    parsed.images[image_id] = image;
  }
  for (const std::string& line : DataLines(dir + "/points3D.txt")) {
    std::istringstream in(line);
    long point_id;
    int r, g, b;
    ParsedModel::Point point;
    in >> point_id >> point.xyz.x() >> point.xyz.y() >> point.xyz.z() >> r >> g >> b >> point.error;
    long image_id;
    size_t index;
    while (in >> image_id >> index) point.track.push_back({image_id, index});
    parsed.points[point_id] = point;
  }
  return parsed;
}

TEST(ColmapModelTest, TracksAndImagePointsAgreeAndReprojectWithColmapConventions) {
  // A random model with exact observations: read back with COLMAP's conventions (cam_from_world,
  // pixel centres at +0.5), every track element must name a 2D point that refers back to the
  // 3D point and lies where the point projects.
  ColmapModel model;
  model.camera = TestCamera();
  for (int k = 0; k < 5; ++k) {
    model.images.push_back({"images/" + std::to_string(k) + ".png",
                            Pose3(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random())});
  }
  for (int i = 0; i < 40; ++i) {
    ColmapPoint point;
    point.position = Eigen::Vector3d::Random() * 3;
    for (int k = 0; k < 5; ++k) {
      const Eigen::Vector3d p_camera = model.images[k].world_T_camera.Inverse() * point.position;
      if (p_camera.z() > 0.1 && std::rand() % 3 != 0) {
        point.track.push_back({k, model.camera.ProjectUndistorted(p_camera)});
      }
    }
    model.points.push_back(point);
  }
  const std::string dir = testing::MakeScratchDir("colmap_random");
  ASSERT_TRUE(WriteColmapModel(dir, model).ok());
  const ParsedModel parsed = Parse(dir);
  ASSERT_EQ(parsed.images.size(), model.images.size());
  ASSERT_EQ(parsed.points.size(), model.points.size());
  size_t observations = 0;
  for (const auto& [point_id, point] : parsed.points) {
    EXPECT_LT(point.error, 1e-9) << "point " << point_id;
    EXPECT_GE(point.error, point.track.empty() ? -1 : 0);
    for (const auto& [image_id, index] : point.track) {
      const ParsedModel::Image& image = parsed.images.at(image_id);
      ASSERT_LT(index, image.points2d.size());
      EXPECT_EQ(image.points2d[index].second, point_id);
      const Eigen::Vector3d p = image.camera_from_world * point.xyz + image.translation;
      const Eigen::Vector2d projected(parsed.fx * p.x() / p.z() + parsed.cx,
                                      parsed.fy * p.y() / p.z() + parsed.cy);
      EXPECT_LT((projected - image.points2d[index].first).norm(), 1e-9);
      ++observations;
    }
  }
  size_t image_points = 0;
  for (const auto& [image_id, image] : parsed.images) image_points += image.points2d.size();
  EXPECT_EQ(observations, image_points);
}

// An equidistant lens is written as COLMAP's OPENCV_FISHEYE with the observations in the stored
// image's pixels: each 2D point of images.txt is where COLMAP's own OPENCV_FISHEYE projection
// (written out here from COLMAP's src/colmap/sensor/models.h) puts the 3D point, to 1e-6 px, and
// ERROR is below 1e-6 px.
TEST(ColmapModelTest, EquidistantLensIsWrittenAsOpenCvFisheyeWithStoredPixels) {
  ColmapModel model;
  model.camera = TestCamera();
  model.camera.model = DistortionModel::kEquidistant;
  model.camera.distortion = {0.02, -0.01, 0.004, -0.0005, 0};
  model.images.push_back({"images/0.png", Pose3(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero())});
  const Eigen::Vector3d positions[] = {{0.2, -0.1, 2}, {-3, 1.5, 1}, {2.5, 2, 0.8}};
  for (const Eigen::Vector3d& position : positions) {
    model.points.push_back({position, {{0, model.camera.ProjectUndistorted(position)}}});
  }
  const std::string dir = testing::MakeScratchDir("colmap_fisheye");
  ASSERT_TRUE(WriteColmapModel(dir, model).ok());
  EXPECT_EQ(Lines(ReadFile(dir + "/cameras.txt")).back(),
            "1 OPENCV_FISHEYE 640 480 500 510 320 240 0.02 -0.01 0.004 -0.0005");
  const ParsedModel parsed = Parse(dir);
  const auto& d = model.camera.distortion;
  for (const auto& [point_id, point] : parsed.points) {
    EXPECT_LT(point.error, 1e-6) << "point " << point_id;
    const Eigen::Vector3d p = point.xyz;  // the image's pose is the identity
    const double r = std::hypot(p.x(), p.y()) / p.z(), theta = std::atan(r), t2 = theta * theta;
    const double theta_d = theta * (1 + t2 * (d[0] + t2 * (d[1] + t2 * (d[2] + t2 * d[3]))));
    const Eigen::Vector2d colmap(parsed.fx * p.x() / p.z() * theta_d / r + parsed.cx,
                                 parsed.fy * p.y() / p.z() * theta_d / r + parsed.cy);
    const auto& [image_id, index] = point.track.at(0);
    EXPECT_LT((colmap - parsed.images.at(image_id).points2d[index].first).norm(), 1e-6)
        << "point " << point_id;
  }
}

TEST(ColmapModelTest, BadModelsAreRejectedWithoutFiles) {
  const std::string dir = testing::MakeScratchDir("colmap_bad");
  ColmapModel spaced = TinyModel();
  spaced.images[1].name = "my image.png";
  const Status name = WriteColmapModel(dir + "/spaced", spaced);
  EXPECT_FALSE(name.ok());
  EXPECT_NE(name.message().find("images.txt: image 1 ('my image.png')"), std::string::npos) << name.message();

  ColmapModel not_finite = TinyModel();
  not_finite.points[2].position.x() = std::numeric_limits<double>::infinity();
  const Status point = WriteColmapModel(dir + "/not_finite", not_finite);
  EXPECT_FALSE(point.ok());
  EXPECT_NE(point.message().find("points3D.txt: point 2"), std::string::npos) << point.message();

  ColmapModel repeated = TinyModel();
  repeated.points[0].id = 2;  // point 1 has none: index + 1 = 2
  const Status ids = WriteColmapModel(dir + "/repeated", repeated);
  EXPECT_FALSE(ids.ok());
  EXPECT_NE(ids.message().find("points3D.txt: point 1 repeats the POINT3D_ID 2"), std::string::npos)
      << ids.message();
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// Given ids name the points in points3D.txt and in images.txt's 2D points.
TEST(ColmapModelTest, PointIdsNameThePointsEverywhere) {
  const std::string dir = testing::MakeScratchDir("colmap_ids");
  ColmapModel model = TinyModel();
  for (size_t i = 0; i < model.points.size(); ++i) model.points[i].id = 100 + static_cast<long>(i) * 10;
  ASSERT_TRUE(WriteColmapModel(dir, model).ok());
  const std::string points = ReadFile(dir + "/points3D.txt");
  const std::string images = ReadFile(dir + "/images.txt");
  for (const std::string id : {"100", "110", "120"}) {
    EXPECT_NE(points.find("\n" + id + " "), std::string::npos) << id;
    EXPECT_NE(images.find(" " + id), std::string::npos) << id;
  }
  EXPECT_EQ(points.find("\n1 "), std::string::npos);
}

}  // namespace
}  // namespace sfm
