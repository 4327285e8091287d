#include "frontend/segments/hough_segments.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

// Edge points every pixel along y = 0.5 x + 20.3 for x in [from, to), gradient along +-normal.
void AddRun(double from, double to, double sign, std::vector<EdgePoint>* points) {
  const Eigen::Vector2d n = Eigen::Vector2d(1, 0.5).normalized(), q(-n.y(), n.x());
  for (double s = 0; from + s * n.x() < to; s += 1.0) {
    EdgePoint p;
    p.x = static_cast<float>(from + s * n.x());
    p.y = static_cast<float>(0.5 * p.x + 20.3);
    p.gx = static_cast<float>(sign * 10 * q.x());
    p.gy = static_cast<float>(sign * 10 * q.y());
    points->push_back(p);
  }
}

TEST(HoughSegmentsTest, FitsTheLineAndEndsAtTheLastEdgePoints) {
  std::vector<EdgePoint> points;
  AddRun(30, 150, +1, &points);
  const LineSegments segments = HoughSegments(points, cv::Size(200, 200), SegmentDetectorOptions());
  ASSERT_EQ(segments.size(), 1u);
  const LineSegment& s = segments[0];
  EXPECT_EQ(s.support, static_cast<int>(points.size()));
  EXPECT_LT(s.fit_rms, 1e-4);
  const Eigen::Vector2d first(points.front().x, points.front().y), last(points.back().x, points.back().y);
  EXPECT_LT(std::min((s.p0 - first).norm(), (s.p1 - first).norm()), 1e-3);
  EXPECT_LT(std::min((s.p0 - last).norm(), (s.p1 - last).norm()), 1e-3);
}

TEST(HoughSegmentsTest, SplitsAtGapsLongerThanMaxGap) {
  SegmentDetectorOptions options;
  options.max_gap = 3;
  std::vector<EdgePoint> points;
  AddRun(20, 80, +1, &points);
  AddRun(82, 140, +1, &points);  // gap of about 2.4 px along the line: bridged
  EXPECT_EQ(HoughSegments(points, cv::Size(200, 200), options).size(), 1u);
  points.clear();
  AddRun(20, 80, +1, &points);
  AddRun(86, 140, +1, &points);  // gap of about 6.7 px: split
  EXPECT_EQ(HoughSegments(points, cv::Size(200, 200), options).size(), 2u);
}

TEST(HoughSegmentsTest, KeepsOppositePolaritiesApart) {
  std::vector<EdgePoint> points;
  AddRun(20, 80, +1, &points);
  AddRun(81, 140, -1, &points);
  const LineSegments segments = HoughSegments(points, cv::Size(200, 200), SegmentDetectorOptions());
  ASSERT_EQ(segments.size(), 2u);
  // Each is oriented with its gradient (the brighter side) along its Normal().
  for (const LineSegment& s : segments) {
    const bool first_run = std::min(s.p0.x(), s.p1.x()) < 50;
    const Eigen::Vector2d gradient = Eigen::Vector2d(-0.5, 1).normalized() * (first_run ? 1 : -1);
    EXPECT_GT(s.Normal().dot(gradient), 0.99);
  }
}

TEST(HoughSegmentsTest, DropsRunsShorterThanMinLength) {
  SegmentDetectorOptions options;
  options.min_length = 30;
  std::vector<EdgePoint> points;
  AddRun(20, 40, +1, &points);
  EXPECT_TRUE(HoughSegments(points, cv::Size(200, 200), options).empty());
}

}  // namespace
}  // namespace sfm
