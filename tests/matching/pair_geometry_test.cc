// PairGeometry: the pose band (3 sigma of the epipolar distance from the odometry noise) and the
// cheirality test, against hand-computed values.
#include "frontend/matching/pair_geometry.h"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "geometry/epipolar.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/matching/junction_similarity.h"

namespace sfm {
namespace {

Eigen::Matrix3d TestK() {
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  return K;
}

// Camera 2 is camera 1 moved by `motion` (metres, camera 1's axes), not turned.
PairGeometry Translated(const Eigen::Vector3d& motion) {
  PairGeometry geometry;
  geometry.K = TestK();
  geometry.camera2_T_camera1 = Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-motion));
  return geometry;
}

TEST(PairGeometryTest, FundamentalAgreesWithFundamentalFromOdometry) {
  const Pose3 base_T_camera(Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5), Eigen::Vector3d(0.2, 0, 0.4));
  const Pose3 world_T_base1(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(1, 2, 0));
  const Pose3 world_T_base2(Eigen::Quaterniond(Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitZ())),
                            Eigen::Vector3d(1.2, 2.1, 0));
  const PairGeometry geometry =
      PairGeometryFromOdometry(TestK(), base_T_camera, world_T_base1, world_T_base2, 0.02, 0.002, 1);
  const Eigen::Matrix3d F = FundamentalFromOdometry(TestK(), base_T_camera, world_T_base1, world_T_base2);
  EXPECT_LT((geometry.Fundamental() - F).norm(), 1e-12 * F.norm());
}

// base_T_camera = identity, the base moved 1 m along x: camera2_T_camera1 = (I, t = (-1, 0, 0)).
// Base noise: w per-axis variance r^2; dt variance s^2 along x (the step), r^2 across. The inverse
// of (Exp(w), t_B + dt) gives w' = -w and dt' = -[t_B]x w - dt, so the covariance of (w', dt') has
// diagonal (r^2, r^2, r^2, s^2, 2 r^2, 2 r^2) and cross terms E[w' dt'^T] = r^2 [t_B]x^T.
TEST(PairGeometryTest, CovarianceFromTheOdometryNoiseModel) {
  const double s = 0.1, r = 0.01;
  const PairGeometry geometry = PairGeometryFromOdometry(
      TestK(), Pose3::Identity(), Pose3::Identity(), Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0)),
      s, r, 1);
  EXPECT_LT((geometry.camera2_T_camera1.translation - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-12);
  Eigen::Matrix<double, 6, 6> expected = Eigen::Matrix<double, 6, 6>::Zero();
  expected.diagonal() << r * r, r * r, r * r, s * s, 2 * r * r, 2 * r * r;
  // E[w' dt'^T] = E[(-w)(-[t]x w)^T] = r^2 [t]x^T with t = (1, 0, 0): [t]x^T(1,2) = 1, (2,1) = -1.
  expected(1, 5) = expected(5, 1) = r * r;
  expected(2, 4) = expected(4, 2) = -r * r;
  EXPECT_LT((geometry.covariance - expected).cwiseAbs().maxCoeff(), 1e-9) << geometry.covariance;
  // Two frames apart: rotation variance 2 r^2 per axis, across the step 2 r^2, along it s^2.
  const PairGeometry two = PairGeometryFromOdometry(
      TestK(), Pose3::Identity(), Pose3::Identity(), Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0)),
      s, r, 2);
  EXPECT_NEAR(two.covariance(0, 0), 2 * r * r, 1e-9);
  EXPECT_NEAR(two.covariance(3, 3), s * s, 1e-9);
  EXPECT_NEAR(two.covariance(4, 4), 4 * r * r, 1e-9);
}

// Sideways motion by 1 m, a point at depth Z = 10 m on the optical axis: x1 = (320, 240),
// x2 = (320 - f / Z, 240) = (270, 240). With m1 = (0, 0, 1), m2 = (-1/Z, 0, 1): the residual
// e = m2 . (t x R m1) moves by omega . (R m1 x (m2 x t)) = omega_x and by dt . (R m1 x m2) =
// -dt_y / Z; both epipolar lines have |(a, b)| = 1/f. So sigma_d = f sqrt(r^2 + (s_y / Z)^2):
// r = 0.01 rad on every axis (only the tilt counts here) and s_y = 0.1 m give 500 sqrt(2e-4) =
// 7.0711 px in each image; the band at 3 sigma with 0.5 px location noise is
// 3 sqrt(50 + 2 * 0.25) = 21.319 px.
TEST(PairGeometryTest, EpipolarSigmaHandComputed) {
  PairGeometry geometry = Translated(Eigen::Vector3d(1, 0, 0));
  geometry.covariance.diagonal() << 1e-4, 1e-4, 1e-4, 0, 0.01, 0;
  const Eigen::Vector2d x1(320, 240), x2(270, 240);
  const EpipolarDistanceSigmas sigmas = EpipolarSigmas(geometry, x1, x2);
  EXPECT_NEAR(sigmas.in_image2, 500 * std::sqrt(2e-4), 1e-9);
  EXPECT_NEAR(sigmas.in_image1, 500 * std::sqrt(2e-4), 1e-9);
  EXPECT_NEAR(EpipolarBand(sigmas.in_image2, 0.5, 3), 21.319005605, 1e-8);
  // Rotation only: f r = 5 px.
  geometry.covariance.diagonal() << 1e-4, 1e-4, 1e-4, 0, 0, 0;
  EXPECT_NEAR(EpipolarSigmas(geometry, x1, x2).in_image2, 5, 1e-9);

  // The matcher's band for the same pair (junctions at x1, x2) is the same number.
  Junction a, b;
  a.location = x1;
  b.location = x2;
  a.segments = {{Eigen::Vector2d(320, 200), -1}, {Eigen::Vector2d(360, 240), -1}};
  b.segments = {{Eigen::Vector2d(270, 200), -1}, {Eigen::Vector2d(310, 240), -1}};
  MatchingOptions options;
  const JunctionSimilarity similarity({a}, {b}, geometry, options);
  EXPECT_NEAR(similarity.BandsOf(0, 0).in_image2, EpipolarBand(5, 0.5, 3), 1e-9);
  EXPECT_NEAR(similarity.BandsOf(0, 0).in_image1, EpipolarBand(5, 0.5, 3), 1e-9);
  options.use_pose_band = false;
  EXPECT_EQ(JunctionSimilarity({a}, {b}, geometry, options).BandsOf(0, 0).in_image2, options.max_epipolar_distance_px);
}

// Forward motion by 1 m, a point at (1, 0, 5) m: x1 = (420, 240), x2 = (445, 240) (away from the
// focus of expansion). v2 = x1 (no rotation), w2 = t_xy - m t_z = (0.2, 0): parallax +25 px. The
// spread of v2 under a pan about y is f (1 + (100/f)^2) r = 520 r px: 5.2 px for r = 0.01.
TEST(PairGeometryTest, ParallaxHandComputed) {
  PairGeometry geometry = Translated(Eigen::Vector3d(0, 0, 1));
  geometry.covariance.diagonal() << 1e-4, 1e-4, 1e-4, 0.01, 0.01, 0.01;
  const Parallax right = ParallaxInImage2(geometry, Eigen::Vector2d(420, 240), Eigen::Vector2d(445, 240));
  EXPECT_NEAR(right.parallax, 25, 1e-9);
  EXPECT_NEAR(right.sigma, 5.2, 1e-9);
  // Moving towards the focus of expansion instead: depth -5 m, behind camera 1.
  const Parallax wrong = ParallaxInImage2(geometry, Eigen::Vector2d(420, 240), Eigen::Vector2d(400, 240));
  EXPECT_NEAR(wrong.parallax, -20, 1e-9);
  // Tolerance 3 sqrt(5.2^2 + 2 * 0.5^2) = 15.74 px: -20 fails, -15 passes.
  EXPECT_TRUE(PassesCheirality(geometry, Eigen::Vector2d(420, 240), Eigen::Vector2d(445, 240), 3, 0.5));
  EXPECT_FALSE(PassesCheirality(geometry, Eigen::Vector2d(420, 240), Eigen::Vector2d(400, 240), 3, 0.5));
  EXPECT_TRUE(PassesCheirality(geometry, Eigen::Vector2d(420, 240), Eigen::Vector2d(405, 240), 3, 0.5));
  // The ray of x1 at the epipole (FOE): no parallax direction, not tested.
  EXPECT_TRUE(std::isinf(ParallaxInImage2(geometry, Eigen::Vector2d(320, 240), Eigen::Vector2d(300, 240)).sigma));
}

// Sideways motion: camera 2 is 1 m to the right, so image points move left. Two candidates of the
// same shape on x1's epipolar line (the row y = 240), one 50 px left (depth 10 m) and one 50 px
// right (depth -10 m, behind both cameras). Both have d = d' = 0 and rho2 = 1 (the horizontal arm
// lies along the epipolar line, the vertical one keeps its length), so only cheirality tells them
// apart.
TEST(PairGeometryTest, MatcherRejectsAPairBehindTheCameras) {
  PairGeometry geometry = Translated(Eigen::Vector3d(1, 0, 0));
  geometry.covariance.diagonal() << 1e-6, 1e-6, 1e-6, 1e-4, 1e-4, 1e-4;
  auto l_at = [](double x) {
    Junction j;
    j.location = Eigen::Vector2d(x, 240);
    j.segments = {{Eigen::Vector2d(x, 200), -1}, {Eigen::Vector2d(x + 40, 240), -1}};
    return j;
  };
  const Junctions a = {l_at(320)};
  const Junctions b = {l_at(270), l_at(370)};
  MatchingOptions options;
  options.use_cheirality = false;
  const JunctionSimilarity without(a, b, geometry, options);
  EXPECT_TRUE(without.Rho(0, 0).Matched());
  EXPECT_TRUE(without.Rho(0, 1).Matched());
  EXPECT_NEAR(without.Rho(0, 1).rho, without.Rho(0, 0).rho, 1e-12);
  options.use_cheirality = true;
  const JunctionSimilarity with(a, b, geometry, options);
  EXPECT_TRUE(with.Rho(0, 0).Matched());
  EXPECT_FALSE(with.Rho(0, 1).Matched());
  EXPECT_FALSE(with.PassesCheirality(0, 1));

  // MatchJunctions: without cheirality the two tie and rule (38) keeps neither; with it, the
  // pair in front is matched.
  TopologyGraph graph_a, graph_b;
  graph_a.edges_of_junction.resize(1);
  graph_b.edges_of_junction.resize(2);
  options.use_cheirality = false;
  EXPECT_TRUE(MatchJunctions(a, graph_a, b, graph_b, geometry, options).empty());
  options.use_cheirality = true;
  const std::vector<JunctionMatch> matches = MatchJunctions(a, graph_a, b, graph_b, geometry, options);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].index_b, 0);
}

}  // namespace
}  // namespace sfm
