#include "frontend/junctions/intersection.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/test_segments.h"

namespace sfm {
namespace {

constexpr double kDeg = M_PI / 180.0;

using testing::Segment;

TEST(IntersectionTest, LineFormOfEquations1And2) {
  // y = 2 from left to right: n = (1, 0), q = (0, 1), rho = 2.
  const SegmentLine line(Segment(0, 2, 10, 2));
  EXPECT_DOUBLE_EQ(line.n.x(), 1);
  EXPECT_DOUBLE_EQ(line.q.y(), 1);
  EXPECT_DOUBLE_EQ(line.rho, 2);
  EXPECT_DOUBLE_EQ(line.length, 10);
}

TEST(IntersectionTest, Equation6OnAxisAlignedLines) {
  // a: y = 2, rho_a = 2, q_a = (0, 1). b: x = 3 downwards, n_b = (0, 1), q_b = (-1, 0), rho_b = -3.
  // p0 = 2*(0, 1) + ((-3 - 2*0) / (n_a.q_b = -1)) * (1, 0) = (3, 2).
  const auto p0 =
      IntersectLines(SegmentLine(Segment(0, 2, 10, 2)), SegmentLine(Segment(3, 5, 3, 10)), 5 * kDeg);
  ASSERT_TRUE(p0.has_value());
  EXPECT_NEAR(p0->x(), 3, 1e-12);
  EXPECT_NEAR(p0->y(), 2, 1e-12);
}

TEST(IntersectionTest, Equation6OnObliqueLines) {
  // (1, 2) + s*(4, 2) = (10, 0) + u*(-2, 6) by hand: s = 25/14, u = 13/14, p0 = (57/7, 39/7).
  const SegmentLine a(Segment(1, 2, 5, 4));
  const SegmentLine b(Segment(10, 0, 8, 6));
  for (const auto& p0 : {IntersectLines(a, b, 5 * kDeg), IntersectLines(b, a, 5 * kDeg)}) {
    ASSERT_TRUE(p0.has_value());
    EXPECT_NEAR(p0->x(), 57.0 / 7.0, 1e-12);
    EXPECT_NEAR(p0->y(), 39.0 / 7.0, 1e-12);
  }
}

TEST(IntersectionTest, NearParallelLinesAreNotIntersected) {
  const SegmentLine a(Segment(0, 0, 100, 0));
  const SegmentLine at_4_degrees(Segment(0, 10, 100, 10 + 100 * std::tan(4 * kDeg)));
  const SegmentLine at_6_degrees(Segment(0, 10, 100, 10 + 100 * std::tan(6 * kDeg)));
  EXPECT_FALSE(IntersectLines(a, at_4_degrees, 5 * kDeg).has_value());
  EXPECT_FALSE(IntersectLines(a, SegmentLine(Segment(0, 10, 100, 10)), 5 * kDeg).has_value());
  const auto p0 = IntersectLines(a, at_6_degrees, 5 * kDeg);
  ASSERT_TRUE(p0.has_value());
  EXPECT_NEAR(p0->x(), -10 / std::tan(6 * kDeg), 1e-9);
  EXPECT_NEAR(p0->y(), 0, 1e-9);
}

}  // namespace
}  // namespace sfm
