// The sub-pixel localisation of each path, on single straight step edges at known positions.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "frontend/segments/segment_detector.h"
#include "frontend/segments/subpixel_edges.h"
#include "tests/segments/synthetic_image.h"

namespace sfm {
namespace {

using testing::Polygon;
using testing::SyntheticImageOptions;

// A half-plane x*cos(a) + y*sin(a) >= offset of grey 170 on 70, blurred (sigma 1), no noise; the
// edge line is returned as a point and unit normal.
cv::Mat StepImage(double angle_deg, double offset, Eigen::Vector2d* point, Eigen::Vector2d* normal) {
  const double a = angle_deg * M_PI / 180;
  *normal = Eigen::Vector2d(std::cos(a), std::sin(a));
  *point = Eigen::Vector2d(64, 64) + offset * *normal;
  const Eigen::Vector2d along(-normal->y(), normal->x());
  const Polygon half_plane{{*point + 500 * along, *point - 500 * along, *point - 500 * along + 500 * *normal,
                            *point + 500 * along + 500 * *normal},
                           170};
  SyntheticImageOptions options;
  options.width = options.height = 128;
  options.background = 70;
  options.noise_sigma = 0;
  return testing::RenderPolygons({half_plane}, options);
}

// Reference path: each Canny/Devernay edge point, away from the image border, lies within
// 0.05 px of the true edge, for phases across a pixel and for axis-aligned and slanted edges.
TEST(SubpixelEdgesTest, EdgePointsLieOnTheTrueEdge) {
  for (const double angle : {0.0, 90.0, 20.0, 45.0, 161.0}) {
    for (const double phase : {0.0, 0.25, 0.5, 0.8}) {
      Eigen::Vector2d point, normal;
      const cv::Mat image = StepImage(angle, phase, &point, &normal);
      const std::vector<EdgePoint> edges = DetectSubpixelEdges(image, 1.0, 2.0, 4.0);
      int inside = 0;
      double worst = 0;
      for (const EdgePoint& e : edges) {
        if (e.x < 8 || e.y < 8 || e.x > 120 || e.y > 120) continue;
        ++inside;
        worst = std::max(worst, std::abs(normal.dot(Eigen::Vector2d(e.x, e.y) - point)));
      }
      EXPECT_GT(inside, 100) << angle << " " << phase;
      EXPECT_LT(worst, 0.05) << "angle " << angle << " phase " << phase;
    }
  }
}

TEST(SubpixelEdgesTest, StepGradientMatchesTheFilterResponse) {
  Eigen::Vector2d point, normal;
  const cv::Mat image = StepImage(0, 0.5, &point, &normal);  // step of 100 grey levels
  const std::vector<EdgePoint> edges = DetectSubpixelEdges(image, 1.5, 1.0, 1.0);
  ASSERT_FALSE(edges.empty());
  double peak = 0;
  for (const EdgePoint& e : edges) peak = std::max(peak, static_cast<double>(std::hypot(e.gx, e.gy)));
  // The image's own blur (sigma 1) adds to the filter's: sqrt(1.5^2 + 1^2) = 1.80.
  EXPECT_NEAR(peak, StepGradient(100, std::hypot(1.5, 1.0)), 0.05 * peak);
}

// Both paths: the fitted line of one long step edge lies within 0.05 px of the truth at every
// phase. Without sub-pixel edge points an axis-aligned edge would be off by up to 0.5 px.
TEST(SubpixelFitTest, BothPathsFitTheStepEdgeLine) {
  for (const SegmentMethod method : {SegmentMethod::kReference, SegmentMethod::kFast}) {
    SegmentDetectorOptions options;
    options.method = method;
    for (const double angle : {0.0, 90.0, 7.0, 33.0, 128.0}) {
      for (const double phase : {0.0, 0.3, 0.5, 0.7}) {
        const std::string where = std::string(method == SegmentMethod::kFast ? "fast" : "reference") + " angle " +
                                  std::to_string(angle) + " phase " + std::to_string(phase);
        Eigen::Vector2d point, normal;
        const LineSegments segments = DetectLineSegments(StepImage(angle, phase, &point, &normal), options);
        const LineSegment* longest = nullptr;
        for (const LineSegment& s : segments) {
          if (!longest || s.Length() > longest->Length()) longest = &s;
        }
        ASSERT_NE(longest, nullptr) << where;
        EXPECT_GT(longest->Length(), 100) << where;
        EXPECT_LT(std::abs(normal.dot(longest->p0 - point)), 0.05) << where;
        EXPECT_LT(std::abs(normal.dot(longest->p1 - point)), 0.05) << where;
      }
    }
  }
}

}  // namespace
}  // namespace sfm
