#include "frontend/junctions/classification.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sfm {
namespace {

constexpr double kTolerance = 5 * M_PI / 180.0;

// A junction at (100, 100) with segments of length 60 pointing at the given image angles (degrees,
// atan2 with y down: 0 right, 90 down, 180 left, 270 up).
Junction Star(std::initializer_list<double> angles_deg) {
  Junction junction;
  junction.location = Eigen::Vector2d(100, 100);
  for (double a : angles_deg) {
    JunctionSegment segment;
    segment.end =
        junction.location + 60 * Eigen::Vector2d(std::cos(a * M_PI / 180), std::sin(a * M_PI / 180));
    junction.segments.push_back(segment);
  }
  OrderClockwise(&junction);
  return junction;
}

TEST(ClassificationTest, ClockwiseOnAHandDrawnCross) {
  // Drawn on screen: arms to 12, 3, 6 and 9 o'clock, given out of order.
  Junction junction;
  junction.location = Eigen::Vector2d(100, 100);
  const Eigen::Vector2d up(100, 40), right(160, 100), down(100, 160), left(40, 100);
  for (const Eigen::Vector2d& end : {down, left, right, up}) junction.segments.push_back({end, -1});
  OrderClockwise(&junction);
  // Clockwise on screen (y down): 12 -> 3 -> 6 -> 9 o'clock.
  ASSERT_EQ(junction.NumSegments(), 4);
  EXPECT_EQ(junction.segments[0].end, up);
  EXPECT_EQ(junction.segments[1].end, right);
  EXPECT_EQ(junction.segments[2].end, down);
  EXPECT_EQ(junction.segments[3].end, left);
}

TEST(ClassificationTest, ClockwiseOnAHandDrawnY) {
  // A Y drawn on screen at (10, 10): one arm up-left to (4, 2), one up-right to (18, 4), the stem
  // down to (10, 20). Read clockwise from the up-left arm: up-right, then down, then up-left.
  Junction junction;
  junction.location = Eigen::Vector2d(10, 10);
  junction.segments = {{Eigen::Vector2d(10, 20), 0}, {Eigen::Vector2d(18, 4), 1}, {Eigen::Vector2d(4, 2), 2}};
  OrderClockwise(&junction);
  EXPECT_EQ(junction.segments[0].line_segment, 2);
  EXPECT_EQ(junction.segments[1].line_segment, 1);
  EXPECT_EQ(junction.segments[2].line_segment, 0);
  // Each step turns clockwise on screen: with y down that is a positive 2-D cross product.
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d a = junction.SegmentDirection(i), b = junction.SegmentDirection((i + 1) % 3);
    EXPECT_GT(a.x() * b.y() - a.y() * b.x(), 0) << i;
  }
}

TEST(ClassificationTest, Types) {
  EXPECT_EQ(ClassifyJunction(Star({0, 90}), kTolerance), JunctionType::kL);
  EXPECT_EQ(ClassifyJunction(Star({270, 30, 150}), kTolerance), JunctionType::kY);
  EXPECT_EQ(ClassifyJunction(Star({0, 60, 120}), kTolerance), JunctionType::kArrow);
  EXPECT_EQ(ClassifyJunction(Star({0, 90, 180}), kTolerance), JunctionType::kT);
  EXPECT_EQ(ClassifyJunction(Star({0, 90, 183}), kTolerance), JunctionType::kT);      // within 5 degrees
  EXPECT_EQ(ClassifyJunction(Star({0, 90, 170}), kTolerance), JunctionType::kArrow);  // 190 degree angle
  EXPECT_EQ(ClassifyJunction(Star({0, 90, 190}), kTolerance), JunctionType::kY);      // 170 degree angle
  EXPECT_EQ(ClassifyJunction(Star({0, 100, 220}), kTolerance), JunctionType::kY);
  EXPECT_EQ(ClassifyJunction(Star({0, 90, 180, 270}), kTolerance), JunctionType::kX);
  EXPECT_EQ(ClassifyJunction(Star({0, 72, 144, 216, 288}), kTolerance), JunctionType::kN);
}

TEST(ClassificationTest, TwoArmsOfOneDetectedSegmentMakeAT) {
  // The bar's arms come from one detected segment: a T even though the location lies 1 px off it.
  Junction junction;
  junction.location = Eigen::Vector2d(50, 51);
  junction.segments = {
      {Eigen::Vector2d(100, 50), 0}, {Eigen::Vector2d(60, 100), 1}, {Eigen::Vector2d(44, 50), 0}};
  OrderClockwise(&junction);
  EXPECT_EQ(ClassifyJunction(junction, 1e-3), JunctionType::kT);
}

}  // namespace
}  // namespace sfm
