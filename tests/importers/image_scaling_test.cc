#include "sequences/importers/image_scaling.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace sfm {
namespace {

TEST(ImageScalingTest, StrechaCameraScaledToQuarterByHand) {
  // entry-P10's K and size; 768 / 3072 = 512 / 2048 = 0.25.
  Camera camera;
  camera.width = 3072;
  camera.height = 2048;
  camera.fx = 2759.48, camera.fy = 2764.16, camera.cx = 1520.69, camera.cy = 1006.81;
  ImageScaleOptions options;  // max_width 768
  const cv::Size size = ScaledImageSize(camera.width, camera.height, options);
  ASSERT_EQ(size, cv::Size(768, 512));
  const Camera scaled = ScaleCamera(camera, size);
  EXPECT_NEAR(scaled.fx, 689.87, 1e-12);
  EXPECT_NEAR(scaled.fy, 691.04, 1e-12);
  EXPECT_NEAR(scaled.cx, 379.7975, 1e-12);  // 0.25 * (1520.69 + 0.5) - 0.5, not 0.25 * 1520.69 = 380.1725
  EXPECT_NEAR(scaled.cy, 251.3275, 1e-12);  // 0.25 * (1006.81 + 0.5) - 0.5
  EXPECT_EQ(scaled.width, 768);
  EXPECT_EQ(scaled.height, 512);
}

TEST(ImageScalingTest, SizesFromScaleOrMaxWidth) {
  ImageScaleOptions options;
  EXPECT_EQ(ScaledImageSize(512, 512, options), cv::Size(512, 512));  // narrower than max_width: kept
  options.max_width = 0;
  EXPECT_EQ(ScaledImageSize(3072, 2048, options), cv::Size(3072, 2048));
  options.scale = 0.3;
  EXPECT_EQ(ScaledImageSize(3072, 2048, options), cv::Size(922, 614));  // 921.6, 614.4 rounded
  options.scale = 1.5;
  EXPECT_FALSE(options.Check().ok());
  options.scale = 0;
  options.max_width = -1;
  EXPECT_FALSE(options.Check().ok());
}

// The scaled K must describe the image cv::resize makes: a blob's centroid moves as K says.
TEST(ImageScalingTest, ScaledCameraMatchesResizedImage) {
  const double x = 20.3, y = 17.6, sigma = 2.5;
  cv::Mat image(48, 64, CV_64F);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      image.at<double>(r, c) = std::exp(-((c - x) * (c - x) + (r - y) * (r - y)) / (2 * sigma * sigma));
    }
  }
  cv::Mat resized;
  cv::resize(image, resized, cv::Size(16, 12), 0, 0, cv::INTER_AREA);
  const cv::Moments moments = cv::moments(resized);
  Camera camera;
  camera.width = 64, camera.height = 48, camera.fx = camera.fy = 50, camera.cx = x, camera.cy = y;
  const Camera scaled = ScaleCamera(camera, resized.size());  // the principal point stands in for the blob
  EXPECT_NEAR(moments.m10 / moments.m00, scaled.cx, 0.01);
  EXPECT_NEAR(moments.m01 / moments.m00, scaled.cy, 0.01);
}

}  // namespace
}  // namespace sfm
