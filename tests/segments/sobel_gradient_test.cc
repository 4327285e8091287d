#include "frontend/segments/sobel_gradient.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <opencv2/imgproc.hpp>

namespace sfm {
namespace {

// SobelMagnitude replaced cv::spatialGradient in the fast path on the promise of equal values, so
// that the segments stay bit-identical: every derivative must equal OpenCV's exactly (tolerance 0),
// borders included, on random images (every grey level, so the extremes +-1020 occur) of odd and
// even sizes down to 3 x 3; magnitude and direction follow their definitions at every pixel.
TEST(SobelMagnitudeTest, EqualsSpatialGradientAndDefinitionsExactly) {
  cv::RNG rng(7);
  const int low = 20;
  for (const cv::Size size :
       {cv::Size(3, 3), cv::Size(4, 7), cv::Size(17, 5), cv::Size(64, 48), cv::Size(131, 97)}) {
    for (int trial = 0; trial < 3; ++trial) {
      cv::Mat image(size, CV_8UC1);
      rng.fill(image, cv::RNG::UNIFORM, 0, 256);
      if (trial == 2) cv::GaussianBlur(image, image, cv::Size(5, 5), 0.7);  // smooth, as in the detector
      cv::Mat gx, gy, magnitude, direction, want_gx, want_gy;
      SobelMagnitude(image, low, &gx, &gy, &magnitude, &direction);
      cv::spatialGradient(image, want_gx, want_gy, 3, cv::BORDER_REPLICATE);
      ASSERT_EQ(cv::countNonZero(gx != want_gx), 0) << size;
      ASSERT_EQ(cv::countNonZero(gy != want_gy), 0) << size;
      for (int y = 0; y < size.height; ++y) {
        for (int x = 0; x < size.width; ++x) {
          const int ax = std::abs(gx.at<int16_t>(y, x)), ay = std::abs(gy.at<int16_t>(y, x));
          ASSERT_EQ(magnitude.at<int16_t>(y, x), ax + ay);
          const bool border = x == 0 || y == 0 || x == size.width - 1 || y == size.height - 1;
          const uint8_t want = border || ax + ay < low ? 0 : ay > ax ? kAlongX : kAlongY;
          ASSERT_EQ(direction.at<uint8_t>(y, x), want) << "at " << x << ", " << y << " of " << size;
        }
      }
    }
  }
}

}  // namespace
}  // namespace sfm
