#include "frontend/segments/line_fit.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace sfm {
namespace {

TEST(LineFitTest, CollinearPointsGiveTheirLineExactly) {
  LineFitAccumulator fit;
  const Eigen::Vector2d origin(812.25, -40.5), direction = Eigen::Vector2d(3, -4).normalized();
  for (int i = 0; i < 10; ++i) fit.Add(origin + (i * 1.7) * direction);
  const FittedLine line = fit.Fit();
  EXPECT_NEAR(std::abs(line.direction.dot(direction)), 1.0, 1e-12);
  EXPECT_NEAR(line.Distance(origin), 0, 1e-9);
  EXPECT_NEAR(line.rms, 0, 1e-6);
}

// Orthogonal regression: perpendicular offsets of +-d about a line give that line and rms d,
// whatever the line's angle (an ordinary y-on-x regression would not, for steep lines).
TEST(LineFitTest, MinimisesPerpendicularDistancesAtAnyAngle) {
  for (const double angle_deg : {0.0, 30.0, 89.0, 90.0, 135.0}) {
    const double a = angle_deg * M_PI / 180;
    const Eigen::Vector2d n(std::cos(a), std::sin(a)), q(-n.y(), n.x()), origin(100, 200);
    LineFitAccumulator fit;
    for (int i = 0; i < 20; ++i) fit.Add(origin + i * n + (i % 2 ? 0.25 : -0.25) * q);
    const FittedLine line = fit.Fit();
    EXPECT_NEAR(std::abs(line.direction.dot(n)), 1.0, 1e-4) << angle_deg;
    EXPECT_NEAR(line.Distance(origin + 10 * n), 0, 0.02) << angle_deg;
    EXPECT_NEAR(line.rms, 0.25, 0.01) << angle_deg;
  }
}

TEST(LineFitTest, MergeEqualsAddingEveryPoint) {
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0, 0.3);
  LineFitAccumulator all, first, second;
  for (int i = 0; i < 30; ++i) {
    const Eigen::Vector2d p(400 + i + noise(random), 90 + 0.5 * i + noise(random));
    all.Add(p);
    (i < 12 ? first : second).Add(p);
  }
  first.Merge(second);
  const FittedLine a = all.Fit(), b = first.Fit();
  EXPECT_EQ(first.count(), all.count());
  EXPECT_NEAR(a.direction.dot(b.direction), 1.0, 1e-12);
  EXPECT_NEAR((a.centroid - b.centroid).norm(), 0, 1e-9);
  EXPECT_NEAR(a.rms, b.rms, 1e-9);
}

// End-points are the projections of the extreme points onto the fitted line (paper section 2).
TEST(LineFitTest, SegmentEndsAreProjectionsOfTheExtremePoints) {
  LineFitAccumulator fit;
  fit.Add(0, 0);
  fit.Add(10, 0);
  const LineSegment s = SegmentOnLine(fit.Fit(), Eigen::Vector2d(-1, 0.4), Eigen::Vector2d(12, -0.3), 7);
  EXPECT_NEAR((s.p0 - Eigen::Vector2d(-1, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR((s.p1 - Eigen::Vector2d(12, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(s.support, 7);
}

}  // namespace
}  // namespace sfm
