#include "sequences/importers/plumb_line_distortion.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_data.h"

namespace sfm {
namespace {

using ::testing::HasSubstr;

constexpr double kF = 500, kC = 255.5;

Eigen::Vector2d Distort(const Eigen::Vector2d& pixel, double k1) {
  const Eigen::Vector2d x = (pixel - Eigen::Vector2d(kC, kC)) / kF;
  return Eigen::Vector2d(kC, kC) + kF * x * (1 + k1 * x.squaredNorm());
}

Eigen::Vector2d Undistort(const Eigen::Vector2d& pixel, double k1) {
  const Eigen::Vector2d distorted = (pixel - Eigen::Vector2d(kC, kC)) / kF;
  Eigen::Vector2d x = distorted;
  for (int i = 0; i < 15; ++i) x = distorted / (1 + k1 * x.squaredNorm());  // |k1 r^2| < 0.03: 1e-15
  return Eigen::Vector2d(kC, kC) + kF * x;
}

// One image per straight world edge: a step from grey 60 to 190 along the line through a and b
// (undistorted pixels), blurred over ~1 px, seen through a lens with radial distortion k1 (each
// pixel takes the value of its undistorted position). The segment's end points are those of the
// edge in the distorted image, as a line detector reports them.
void AddEdge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double k1, std::vector<cv::Mat>* images,
             std::vector<PlumbLineSegment>* segments) {
  const Eigen::Vector2d direction = (b - a).normalized();
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  cv::Mat image(512, 512, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const double side = (Undistort(Eigen::Vector2d(x, y), k1) - a).dot(normal);
      image.at<unsigned char>(y, x) = cv::saturate_cast<unsigned char>(125 + 65 * std::tanh(side / 0.7));
    }
  }
  segments->push_back({static_cast<int>(images->size()), Distort(a, k1), Distort(b, k1)});
  images->push_back(image);
}

// Edges like a corridor's: vertical and horizontal ones 80-200 px from the centre and two
// diagonals, 300-400 px long.
void CorridorEdges(double k1, std::vector<cv::Mat>* images, std::vector<PlumbLineSegment>* segments) {
  for (double offset : {-200.0, -140.0, -80.0, 80.0, 140.0, 200.0}) {
    AddEdge(Eigen::Vector2d(kC + offset, kC - 190), Eigen::Vector2d(kC + offset, kC + 190), k1, images,
            segments);
    AddEdge(Eigen::Vector2d(kC - 190, kC + offset), Eigen::Vector2d(kC + 190, kC + offset), k1, images,
            segments);
  }
  AddEdge(Eigen::Vector2d(kC - 150, kC - 60), Eigen::Vector2d(kC + 60, kC + 150), k1, images, segments);
  AddEdge(Eigen::Vector2d(kC - 60, kC + 180), Eigen::Vector2d(kC + 180, kC - 60), k1, images, segments);
}

Eigen::Matrix3d K() {
  Eigen::Matrix3d K;
  K << kF, 0, kC, 0, kF, kC, 0, 0, 1;
  return K;
}

// A barrel distortion like the VGG Corridor's (k1 -0.06: ~1-3 px of bow on these edges) is
// recovered from the edges' bows to 0.003, and no distortion reads as |k1| < 0.003.
TEST(PlumbLineDistortionTest, RecoversRadialDistortionFromStraightEdges) {
  for (double k1 : {-0.06, 0.0, 0.04}) {
    std::vector<cv::Mat> images;
    std::vector<PlumbLineSegment> segments;
    CorridorEdges(k1, &images, &segments);
    PlumbLineEstimate estimate;
    ASSERT_TRUE(EstimateRadialDistortionFromEdges(images, segments, K(), PlumbLineOptions(), &estimate).ok());
    EXPECT_EQ(estimate.edges, 14);
    EXPECT_NEAR(estimate.k1, k1, 0.003) << "k1 " << k1;
    EXPECT_LT(estimate.k1_sigma, 0.003) << "k1 " << k1;
  }
}

// Short segments carry no usable bow and are skipped; with too few long ones there is no estimate.
TEST(PlumbLineDistortionTest, RefusesTooFewLongEdges) {
  std::vector<cv::Mat> images;
  std::vector<PlumbLineSegment> segments;
  AddEdge(Eigen::Vector2d(kC + 150, kC - 190), Eigen::Vector2d(kC + 150, kC + 190), -0.06, &images,
          &segments);
  AddEdge(Eigen::Vector2d(kC - 30, kC - 40), Eigen::Vector2d(kC - 30, kC + 40), -0.06, &images, &segments);
  PlumbLineEstimate estimate;
  EXPECT_THAT(
      EstimateRadialDistortionFromEdges(images, segments, K(), PlumbLineOptions(), &estimate).message(),
      HasSubstr("1 long clean straight edges; at least 3 are needed"));
  segments.push_back({7, Eigen::Vector2d(0, 0), Eigen::Vector2d(200, 0)});
  EXPECT_THAT(
      EstimateRadialDistortionFromEdges(images, segments, K(), PlumbLineOptions(), &estimate).message(),
      HasSubstr("segment of image 7 out of range"));
}

// The VGG Corridor's long straight edges (bt.NNN.lines) bow as a barrel distortion bends them.
// Measured (median K of the P files): k1 -0.0612 +- 0.0032 from 84 edges; each half of the views on
// its own agrees with the other within their sigmas (the held-out check of the estimate).
TEST(PlumbLineDistortionTest, CorridorEdgesShowABarrelDistortion) {
  const std::string data = testing::SharedDataDir("vgg-corridor");
  if (data.empty()) GTEST_SKIP() << "../shared/data/vgg-corridor is absent";
  std::vector<cv::Mat> images;
  std::vector<PlumbLineSegment> even, odd, all;
  for (int v = 0; v < 11; ++v) {
    char name[64];
    std::snprintf(name, sizeof(name), "%s/bt.%03d.pgm", data.c_str(), v);
    images.push_back(cv::imread(name, cv::IMREAD_GRAYSCALE));
    ASSERT_FALSE(images.back().empty()) << name;
    std::snprintf(name, sizeof(name), "%s/bt.%03d.lines", data.c_str(), v);
    std::ifstream in(name);
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream fields(line);
      double x0, y0, x1, y1;
      if (!(fields >> x0 >> y0 >> x1 >> y1)) continue;
      const PlumbLineSegment segment{v, Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1)};
      all.push_back(segment);
      (v % 2 == 0 ? even : odd).push_back(segment);
    }
  }
  Eigen::Matrix3d K;
  K << 502.616, 0, 295.385, 0, 506.404, 266.427, 0, 0, 1;  // the median of the P files' K
  PlumbLineEstimate estimate[3];
  const std::vector<PlumbLineSegment>* sets[3] = {&all, &even, &odd};
  const char* names[3] = {"all views", "even views", "odd views"};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(
        EstimateRadialDistortionFromEdges(images, *sets[i], K, PlumbLineOptions(), &estimate[i]).ok());
    std::cout << "[ figure   ] " << names[i] << ": k1 " << estimate[i].k1 << " +- " << estimate[i].k1_sigma
              << " from " << estimate[i].edges << " edges\n";
  }
  EXPECT_GT(estimate[0].edges, 60);
  EXPECT_LT(estimate[0].k1, -0.04);  // a barrel distortion, clearly: measured -0.061 +- 0.003
  EXPECT_GT(estimate[0].k1, -0.08);
  EXPECT_LT(std::abs(estimate[1].k1 - estimate[2].k1),
            3 * std::hypot(estimate[1].k1_sigma, estimate[2].k1_sigma));
}

}  // namespace
}  // namespace sfm
