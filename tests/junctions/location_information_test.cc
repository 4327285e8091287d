#include "frontend/junctions/location_information.h"

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A junction at the origin with one segment of 20 px at each angle (radians, image axes), each
// from its own detected line segment unless `lines` gives them.
Junction JunctionWithSegments(const std::vector<double>& angles, const std::vector<int>& lines = {}) {
  Junction junction;
  for (size_t i = 0; i < angles.size(); ++i) {
    JunctionSegment segment;
    segment.end = 20 * Eigen::Vector2d(std::cos(angles[i]), std::sin(angles[i]));
    segment.line_segment = lines.empty() ? static_cast<int>(i) : lines[i];
    junction.segments.push_back(segment);
  }
  return junction;
}

TEST(LocationSqrtInformationTest, RightAngleCornerIsTheIdentity) {
  const Eigen::Matrix2d W = LocationSqrtInformation(JunctionWithSegments({0.3, 0.3 + kPi / 2}));
  EXPECT_TRUE(W.isApprox(Eigen::Matrix2d::Identity(), 1e-12)) << W;
}

// Two lines theta apart: information 1 -+ cos(theta) along and across the bisector; at 30 degrees
// its square root is 0.3660 along the bisector (known 2.73x less well than at a right angle) and
// 1.3660 across it.
TEST(LocationSqrtInformationTest, ThirtyDegreeCornerIsWeakAlongItsBisector) {
  const double theta = kPi / 6;
  const Eigen::Matrix2d W = LocationSqrtInformation(JunctionWithSegments({0, theta}));
  const Eigen::Vector2d bisector(std::cos(theta / 2), std::sin(theta / 2));
  const Eigen::Vector2d across(-bisector.y(), bisector.x());
  EXPECT_NEAR((W * bisector - std::sqrt(1 - std::cos(theta)) * bisector).norm(), 0, 1e-12);
  EXPECT_NEAR((W * across - std::sqrt(1 + std::cos(theta)) * across).norm(), 0, 1e-12);
  EXPECT_NEAR(std::sqrt(1 - std::cos(theta)), 0.3660, 1e-4);
}

// A T may be an occlusion: only its bar (one detected line seen as two junction segments) fixes
// the location, across itself; along the bar the information is the floor (0.01: a square root of
// 0.1), whatever the stem. The bar found by its line segment, and by its opposite directions.
TEST(LocationSqrtInformationTest, TIsKnownAcrossItsBarOnly) {
  for (const std::vector<int>& lines : {std::vector<int>{7, 8, 7}, std::vector<int>{}}) {
    Junction t = JunctionWithSegments({0.4, 0.4 + 1.2, 0.4 + kPi}, lines);
    t.type = JunctionType::kT;
    const Eigen::Matrix2d W = LocationSqrtInformation(t);
    const Eigen::Vector2d along(std::cos(0.4), std::sin(0.4));
    const Eigen::Vector2d across(-along.y(), along.x());
    EXPECT_NEAR((W * across - across).norm(), 0, 1e-12) << W;
    EXPECT_NEAR((W * along - 0.1 * along).norm(), 0, 1e-12) << W;
  }
}

// An X may be two lines at different depths: its location has only the floor's information.
TEST(LocationSqrtInformationTest, XHasOnlyTheFloor) {
  Junction x = JunctionWithSegments({0, kPi / 2, kPi, 3 * kPi / 2}, {1, 2, 1, 2});
  x.type = JunctionType::kX;
  EXPECT_TRUE(LocationSqrtInformation(x).isApprox(0.1 * Eigen::Matrix2d::Identity(), 1e-12));
  x.type = JunctionType::kN;  // the same lines read as a 3D junction: each once, the identity
  EXPECT_TRUE(LocationSqrtInformation(x).isApprox(Eigen::Matrix2d::Identity(), 1e-12));
}

// The whitened error is the distances the location's move puts between it and each line:
// |W d|^2 = sum over the lines of (n_i . d)^2, for any move d (three lines, random moves).
TEST(LocationSqrtInformationTest, WhitenedMoveIsTheDistancesFromTheLines) {
  const std::vector<double> angles = {0.2, 1.9, 4.0};
  const Eigen::Matrix2d W = LocationSqrtInformation(JunctionWithSegments(angles));
  std::mt19937 engine(3);
  std::uniform_real_distribution<double> uniform(-2, 2);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector2d move(uniform(engine), uniform(engine));
    double sum = 0;
    for (const double angle : angles) {
      const Eigen::Vector2d normal(-std::sin(angle), std::cos(angle));
      sum += std::pow(normal.dot(move), 2);
    }
    EXPECT_NEAR((W * move).squaredNorm(), sum, 1e-12);
  }
}

// Two segments of different detected lines, 1 degree from one line: the direction along them is
// almost unknown; its information is raised to min_information (0.01: a square root of 0.1).
TEST(LocationSqrtInformationTest, NearlyOneLineIsRaisedToTheFloor) {
  const Eigen::Matrix2d W = LocationSqrtInformation(JunctionWithSegments({0, kPi - kPi / 180}));
  EXPECT_NEAR((W * Eigen::Vector2d(std::cos(-kPi / 360), std::sin(-kPi / 360))).norm(), 0.1, 1e-9);
  EXPECT_NEAR(W.determinant(), 0.1 * std::sqrt(1 + std::cos(kPi / 180)), 1e-9);  // across: 1 + cos(1 deg)
}

}  // namespace
}  // namespace sfm
