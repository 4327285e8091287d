// The local depth range test of the guided pass (frontend/matching/depth_range.h).
#include "frontend/matching/depth_range.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "tests/matching/synthetic_views.h"

namespace sfm {
namespace {

using testing::TwoViews;

PairGeometry ExactGeometry(const TwoViews& views) {
  PairGeometry geometry;
  geometry.K = views.K;
  geometry.camera2_T_camera1 = views.world_T_camera2.Inverse() * views.world_T_camera1;
  // A small rotation uncertainty: the tolerance then has a pose part as well as the location part.
  geometry.covariance.diagonal() << 1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6;
  return geometry;
}

// Camera 1 is the world frame in MakeTwoViews, so a point's depth in camera 1 is its z.
TEST(DepthRangeTest, ParallaxGivesTheInverseDepthOfTheTriangulatedPoint) {
  const TwoViews views = testing::MakeTwoViews();
  const PairGeometry geometry = ExactGeometry(views);
  const double t_z = geometry.camera2_T_camera1.translation.z();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(-2, 2), y(-1.5, 1.5), z(0.8, 30);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d point(x(rng), y(rng), z(rng));
    const Eigen::Vector2d x1 = views.Project(0, point), x2 = views.Project(1, point);
    const ParallaxFrame frame = ParallaxFrameOf(geometry, x1);
    ASSERT_TRUE(frame.tested);
    const double parallax = (x2 - frame.v).dot(frame.direction);
    // x2 lies on the line through v2 along the direction (exact geometry): no sideways part.
    EXPECT_NEAR((x2 - frame.v - parallax * frame.direction).norm(), 0, 1e-9);
    EXPECT_NEAR(InverseDepthOfParallax(frame, t_z, parallax), 1 / point.z(), 1e-9 / point.z());
    EXPECT_NEAR(ParallaxOfInverseDepth(frame, t_z, 1 / point.z()), parallax, 1e-9 * (1 + std::abs(parallax)));
  }
}

// Verified points on two planes (a floor 1.2 m below camera 1 and a wall across at 8 m); a
// junction's partner on either surface at its own depth passes, the same ray's point at a third of
// that depth (3x the inverse depth, far beyond the 2.576-sigma tolerance of 0.5 px locations)
// fails, and so does a floor point's at ten times its depth (beyond everything around it).
TEST(DepthRangeTest, PassesPointsOnTheSurfacesAroundAndRejectsNearerOrFartherOnes) {
  const TwoViews views = testing::MakeTwoViews();
  const PairGeometry geometry = ExactGeometry(views);
  std::vector<Eigen::Vector3d> points;
  for (double x = -1.5; x <= 1.5; x += 0.5) {
    for (double z = 3; z <= 7.5; z += 0.75) points.emplace_back(x, 1.2, z);  // floor (y down)
    for (double y = -1; y <= 1.1; y += 0.5) points.emplace_back(x, y, 8);    // wall
  }
  std::vector<Eigen::Vector2d> x1, x2, locations;
  std::vector<int> source;
  for (size_t k = 0; k < points.size(); ++k) {
    x1.push_back(views.Project(0, points[k]));
    x2.push_back(views.Project(1, points[k]));
    source.push_back(static_cast<int>(k));
    locations.push_back(x1.back());
  }
  const LocalDepthRange range(geometry, x1, x2, source, locations, /*neighbours=*/12, /*gate_sigmas=*/2.576,
                              /*location_sigma_px=*/0.5);
  const Eigen::Vector3d camera1 = views.world_T_camera1.translation;
  int tested = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    if (!range.IntervalOf(static_cast<int>(k)).tested) continue;
    ++tested;
    // Its own partner: inside the range of the 12 other verified points nearest to it.
    EXPECT_TRUE(range.Passes(static_cast<int>(k), x2[k])) << k;
    const Eigen::Vector3d nearer = camera1 + (points[k] - camera1) / 3.0;
    EXPECT_FALSE(range.Passes(static_cast<int>(k), views.Project(1, nearer))) << k;
    // Farther: only where the parallax says so. Ten times the depth of a floor point up to 4.5 m
    // is beyond the wall at 8 m; the wall's own points (3 px of parallax, a 1.9 px tolerance)
    // cannot be told from infinity.
    if (points[k].y() == 1.2 && points[k].z() <= 4.5) {
      EXPECT_FALSE(
          range.Passes(static_cast<int>(k), views.Project(1, camera1 + (points[k] - camera1) * 10.0)))
          << k;
    }
  }
  EXPECT_EQ(tested, static_cast<int>(points.size()));
}

// One wrong verified correspondence: floor point m's image in camera 1 paired with the image of the
// point at a third of its depth. Unscreened, it widens the range of the junctions around m up to
// its inverse depth (3 / Z_m), so a partner of m's nearest neighbour k at that inverse depth
// passes; screened (the default), it fails the test against the other verified points, is dropped,
// and that partner fails.
TEST(DepthRangeTest, ScreeningDropsAWrongVerifiedMatchThatWouldWidenTheRange) {
  const TwoViews views = testing::MakeTwoViews();
  const PairGeometry geometry = ExactGeometry(views);
  std::vector<Eigen::Vector3d> points;
  for (double x = -1.5; x <= 1.5; x += 0.5) {
    for (double z = 3; z <= 7.5; z += 0.75) points.emplace_back(x, 1.2, z);
  }
  std::vector<Eigen::Vector2d> x1, x2;
  std::vector<int> source;
  for (size_t k = 0; k < points.size(); ++k) {
    x1.push_back(views.Project(0, points[k]));
    x2.push_back(views.Project(1, points[k]));
    source.push_back(static_cast<int>(k));
  }
  const Eigen::Vector3d m(0, 1.2, 3.75);
  x1.push_back(views.Project(0, m));
  x2.push_back(views.Project(1, m / 3.0));  // camera 1 at the origin
  source.push_back(static_cast<int>(points.size()));
  // k: the floor point nearest to m in image 1 (other than m itself).
  int k = -1;
  for (size_t j = 0; j < points.size(); ++j) {
    if ((points[j] - m).norm() < 1e-9) continue;
    if (k < 0 || (x1[j] - x1.back()).norm() < (x1[static_cast<size_t>(k)] - x1.back()).norm())
      k = static_cast<int>(j);
  }
  ASSERT_GE(k, 0);
  // On k's ray at inverse depth 3 / Z_m.
  const Eigen::Vector3d candidate =
      points[static_cast<size_t>(k)] / points[static_cast<size_t>(k)].z() * (m.z() / 3.0);
  const std::vector<Eigen::Vector2d> locations = {x1[static_cast<size_t>(k)]};
  std::vector<int> source_k = source;
  for (int& s : source_k) s = s == k ? 0 : s + 1;  // junction 0 of `locations` is k
  const LocalDepthRange unscreened(geometry, x1, x2, source_k, locations, 12, 2.576, 0.5,
                                   /*screen_verified=*/false);
  const LocalDepthRange screened(geometry, x1, x2, source_k, locations, 12, 2.576, 0.5,
                                 /*screen_verified=*/true);
  EXPECT_TRUE(unscreened.Passes(0, views.Project(1, candidate)));
  EXPECT_FALSE(screened.Passes(0, views.Project(1, candidate)));
  // k's own partner passes either way.
  EXPECT_TRUE(unscreened.Passes(0, x2[static_cast<size_t>(k)]));
  EXPECT_TRUE(screened.Passes(0, x2[static_cast<size_t>(k)]));
}

// The grid search finds the same neighbours as a brute-force search: random verified points at
// 2-20 m in the middle of the image, junctions anywhere (also outside the verified points' box).
TEST(DepthRangeTest, IntervalsAgreeWithABruteForceNeighbourSearch) {
  const TwoViews views = testing::MakeTwoViews();
  const PairGeometry geometry = ExactGeometry(views);
  const double t_z = geometry.camera2_T_camera1.translation.z();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5), depth(2, 20), px(0, 640), py(0, 480);
  std::vector<Eigen::Vector2d> x1, x2, locations;
  std::vector<int> source;
  std::vector<double> q;
  for (int k = 0; k < 80; ++k) {
    const double z = depth(rng);
    const Eigen::Vector3d point(u(rng) * z, u(rng) * z, z);
    x1.push_back(views.Project(0, point));
    x2.push_back(views.Project(1, point));
    source.push_back(k < 20 ? k : 1000 + k);  // the first 20 are junctions 0..19 below
    q.push_back(1 / z);
  }
  for (int k = 0; k < 20; ++k) locations.push_back(x1[static_cast<size_t>(k)]);
  for (int k = 0; k < 40; ++k) locations.emplace_back(px(rng), py(rng));
  const int neighbours = 12;
  const LocalDepthRange range(geometry, x1, x2, source, locations, neighbours, 2.576, 0.5,
                              /*screen_verified=*/false);
  for (size_t a = 0; a < locations.size(); ++a) {
    std::vector<std::pair<double, double>> by_distance;  // (distance, q)
    for (size_t k = 0; k < x1.size(); ++k) {
      if (source[k] == static_cast<int>(a)) continue;
      by_distance.emplace_back((x1[k] - locations[a]).norm(), q[k]);
    }
    std::sort(by_distance.begin(), by_distance.end());
    double q_low = 1e300, q_high = -1e300;
    for (int k = 0; k < neighbours; ++k) {
      q_low = std::min(q_low, by_distance[static_cast<size_t>(k)].second);
      q_high = std::max(q_high, by_distance[static_cast<size_t>(k)].second);
    }
    const ParallaxFrame frame = ParallaxFrameOf(geometry, locations[a]);
    ASSERT_TRUE(frame.tested);
    const double tolerance = EpipolarBand(frame.sigma, 0.5, 2.576);
    const LocalDepthRange::Interval& interval = range.IntervalOf(static_cast<int>(a));
    ASSERT_TRUE(interval.tested);
    EXPECT_NEAR(interval.lo, ParallaxOfInverseDepth(frame, t_z, q_low) - tolerance, 1e-6) << a;
    EXPECT_NEAR(interval.hi, ParallaxOfInverseDepth(frame, t_z, q_high) + tolerance, 1e-6) << a;
  }
}

// Without verified neighbours (or where the ray has no parallax direction) there is no test.
TEST(DepthRangeTest, NoNeighboursNoTest) {
  const TwoViews views = testing::MakeTwoViews();
  const PairGeometry geometry = ExactGeometry(views);
  const Eigen::Vector2d x1 = views.Project(0, Eigen::Vector3d(0.5, 0.2, 5));
  const LocalDepthRange range(geometry, {x1}, {views.Project(1, Eigen::Vector3d(0.5, 0.2, 5))}, {0}, {x1}, 12,
                              2.576, 0.5);
  EXPECT_FALSE(range.IntervalOf(0).tested);  // its only verified correspondence is itself
  EXPECT_TRUE(range.Passes(0, views.Project(1, Eigen::Vector3d(0.1, 0.04, 1))));
}

}  // namespace
}  // namespace sfm
