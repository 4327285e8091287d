#include "geometry/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

namespace sfm {
namespace {

// A measured figure for the test report (gtest XML), in scientific notation.
std::string Figure(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3e", value);
  return text;
}

// 640x480 with strong, realistic barrel distortion (wide-angle lens).
Camera DistortedCamera() {
  Camera camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = 500;
  camera.fy = 505;
  camera.cx = 319.5;
  camera.cy = 241.0;
  camera.distortion = {-0.3, 0.1, 1e-3, -1e-3, -0.02};
  return camera;
}

TEST(CameraTest, DistortThenUndistortNormalisedRoundTripBelow1e10) {
  const Camera camera = DistortedCamera();
  double max_error = 0;
  for (double y = -0.5; y <= 0.5; y += 0.05) {
    for (double x = -0.65; x <= 0.65; x += 0.05) {
      const Eigen::Vector2d u(x, y);
      max_error = std::max(max_error, (camera.Undistort(camera.Distort(u)) - u).norm());
    }
  }
  EXPECT_LT(max_error, 1e-10);
}

TEST(CameraTest, PixelRoundTripsAcrossTheImageBelow1e6Pixels) {
  const Camera camera = DistortedCamera();
  double max_error = 0;
  for (int y = 0; y < camera.height; y += 4) {
    for (int x = 0; x < camera.width; x += 4) {
      const Eigen::Vector2d p(x, y);
      // Stored pixel -> undistorted -> stored, and undistorted pixel -> stored -> undistorted.
      max_error = std::max(max_error, (camera.DistortPixel(camera.UndistortPixel(p)) - p).norm());
      max_error = std::max(max_error, (camera.UndistortPixel(camera.DistortPixel(p)) - p).norm());
    }
  }
  RecordProperty("max_round_trip_error_px", Figure(max_error));
  EXPECT_LT(max_error, 1e-6);
}

TEST(CameraTest, NoDistortionIsTheIdentityExactly) {
  Camera camera = DistortedCamera();
  camera.distortion = {0, 0, 0, 0, 0};
  EXPECT_FALSE(camera.HasDistortion());
  const Eigen::Vector2d p(12.25, 400.5);
  EXPECT_EQ(camera.UndistortPixel(p), p);
  EXPECT_LT((camera.DistortPixel(p) - p).norm(), 1e-12);
}

TEST(CameraTest, ProjectAgreesWithCvProjectPointsTo1e9Pixels) {
  const Camera camera = DistortedCamera();
  std::vector<cv::Point3d> points;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d p = Eigen::Vector3d::Random().cwiseProduct(Eigen::Vector3d(2, 1.5, 1)) +
                              Eigen::Vector3d(0, 0, 4);
    points.emplace_back(p.x(), p.y(), p.z());
  }
  const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const std::vector<double> coefficients(camera.distortion.begin(), camera.distortion.end());
  std::vector<cv::Point2d> projected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, coefficients, projected);
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d ours = camera.Project({points[i].x, points[i].y, points[i].z});
    EXPECT_NEAR(ours.x(), projected[i].x, 1e-9);
    EXPECT_NEAR(ours.y(), projected[i].y, 1e-9);
  }
}

TEST(CameraTest, UndistortPixelOfProjectionIsProjectUndistortedBelow1e6Pixels) {
  const Camera camera = DistortedCamera();
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d p = Eigen::Vector3d::Random().cwiseProduct(Eigen::Vector3d(2, 1.5, 1)) +
                              Eigen::Vector3d(0, 0, 4);
    EXPECT_LT((camera.UndistortPixel(camera.Project(p)) - camera.ProjectUndistorted(p)).norm(), 1e-6);
  }
  EXPECT_LT((camera.ProjectUndistorted({1, -2, 4}) - Eigen::Vector2d(319.5 + 125, 241.0 - 252.5)).norm(), 1e-12);
}

TEST(CameraTest, UndistortImageWithoutDistortionIsAnEqualCopy) {
  Camera camera = DistortedCamera();
  camera.distortion = {0, 0, 0, 0, 0};
  cv::Mat image(camera.height, camera.width, CV_8UC1);
  cv::randu(image, 0, 255);
  const cv::Mat undistorted = camera.UndistortImage(image);
  EXPECT_NE(undistorted.data, image.data);
  EXPECT_EQ(cv::norm(undistorted, image, cv::NORM_INF), 0);
}

// The undistorted image at pixel q must show what the stored image shows at DistortPixel(q).
// Tolerance 0.2 grey levels of a 200-level sinusoid: OpenCV's remap interpolates at 1/32 px.
TEST(CameraTest, UndistortImageSamplesTheStoredImageAtDistortPixelWithin0p2Levels) {
  const Camera camera = DistortedCamera();
  auto intensity = [](double x, double y) { return 128 + 60 * std::sin(x / 20) + 40 * std::cos(y / 15); };
  cv::Mat image(camera.height, camera.width, CV_32FC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image.at<float>(y, x) = static_cast<float>(intensity(x, y));
  }
  const cv::Mat undistorted = camera.UndistortImage(image);
  ASSERT_EQ(undistorted.size(), image.size());
  int checked = 0;
  for (int y = 0; y < camera.height; y += 7) {
    for (int x = 0; x < camera.width; x += 7) {
      const Eigen::Vector2d source = camera.DistortPixel(Eigen::Vector2d(x, y));
      if (source.x() < 1 || source.y() < 1 || source.x() > camera.width - 2 || source.y() > camera.height - 2) {
        continue;
      }
      EXPECT_NEAR(undistorted.at<float>(y, x), intensity(source.x(), source.y()), 0.2) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 3000);
}

// 640x480 equidistant fisheye of about 150 degrees across the diagonal (make_sequence --lens
// equidistant's focal length), with coefficients of a real fisheye calibration's size.
Camera FisheyeCamera() {
  Camera camera = DistortedCamera();
  camera.model = DistortionModel::kEquidistant;
  camera.fx = camera.fy = 305.6;
  camera.cx = 319.5;
  camera.cy = 239.5;
  camera.distortion = {0.02, -0.01, 4e-3, -6e-4, 0};
  return camera;
}

TEST(CameraTest, ParsesTheDistortionModelNames) {
  DistortionModel model = DistortionModel::kRadTan;
  EXPECT_TRUE(ParseDistortionModel("equidistant", &model));
  EXPECT_EQ(model, DistortionModel::kEquidistant);
  EXPECT_STREQ(DistortionModelName(model), "equidistant");
  EXPECT_TRUE(ParseDistortionModel("radtan", &model));
  EXPECT_EQ(model, DistortionModel::kRadTan);
  EXPECT_FALSE(ParseDistortionModel("plumb_bob", &model));
}

// An equidistant lens with zero coefficients is still the f-theta projection, not the pinhole.
TEST(CameraTest, EquidistantLensAlwaysHasDistortion) {
  Camera camera = FisheyeCamera();
  camera.distortion = {0, 0, 0, 0, 0};
  EXPECT_TRUE(camera.HasDistortion());
  // theta = 45 degrees lands at f * pi / 4 from the principal point.
  EXPECT_NEAR(camera.Project({1, 0, 1}).x() - camera.cx, camera.fx * M_PI / 4, 1e-9);
  EXPECT_EQ(camera.DistortionCoefficients().cols, 4);
}

TEST(CameraTest, EquidistantProjectAgreesWithCvFisheyeProjectPointsTo1e9Pixels) {
  const Camera camera = FisheyeCamera();
  std::vector<cv::Point3d> points;
  for (int i = 0; i < 200; ++i) {
    // Up to about 70 degrees off axis.
    const Eigen::Vector3d p =
        Eigen::Vector3d::Random().cwiseProduct(Eigen::Vector3d(2, 1.5, 0.4)) + Eigen::Vector3d(0, 0, 0.8);
    points.emplace_back(p.x(), p.y(), p.z());
  }
  const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  std::vector<cv::Point2d> projected;
  cv::fisheye::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K,
                             camera.DistortionCoefficients());
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d ours = camera.Project({points[i].x, points[i].y, points[i].z});
    EXPECT_NEAR(ours.x(), projected[i].x, 1e-9);
    EXPECT_NEAR(ours.y(), projected[i].y, 1e-9);
  }
}

// Every stored pixel of the 150-degree fisheye, corners included (75 degrees off axis), comes back
// from the undistorted plane to 1e-6 px.
TEST(CameraTest, EquidistantPixelRoundTripsAcrossTheImageBelow1e6Pixels) {
  const Camera camera = FisheyeCamera();
  double max_error = 0;
  for (int y = 0; y < camera.height; y += 4) {
    for (int x = 0; x < camera.width; x += 4) {
      const Eigen::Vector2d p(x, y);
      max_error = std::max(max_error, (camera.DistortPixel(camera.UndistortPixel(p)) - p).norm());
    }
  }
  for (double y = -1.5; y <= 1.5; y += 0.1) {
    for (double x = -2.5; x <= 2.5; x += 0.1) {
      const Eigen::Vector2d u(x, y);
      max_error = std::max(max_error, camera.fx * (camera.Undistort(camera.Distort(u)) - u).norm());
    }
  }
  RecordProperty("max_round_trip_error_px", Figure(max_error));
  EXPECT_LT(max_error, 1e-6);
}

// The fisheye undistorted image samples the stored image at DistortPixel, as the radtan one
// (cv::fisheye::initUndistortRectifyMap), to 0.2 grey levels of a 200-level sinusoid.
TEST(CameraTest, EquidistantUndistortImageSamplesTheStoredImageAtDistortPixelWithin0p2Levels) {
  const Camera camera = FisheyeCamera();
  auto intensity = [](double x, double y) { return 128 + 60 * std::sin(x / 20) + 40 * std::cos(y / 15); };
  cv::Mat image(camera.height, camera.width, CV_32FC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) image.at<float>(y, x) = static_cast<float>(intensity(x, y));
  }
  const cv::Mat undistorted = camera.UndistortImage(image);
  int checked = 0;
  for (int y = 0; y < camera.height; y += 7) {
    for (int x = 0; x < camera.width; x += 7) {
      const Eigen::Vector2d source = camera.DistortPixel(Eigen::Vector2d(x, y));
      EXPECT_NEAR(undistorted.at<float>(y, x), intensity(source.x(), source.y()), 0.2) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 6000);
}

}  // namespace
}  // namespace sfm
