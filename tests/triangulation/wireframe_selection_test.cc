// Landmark uncertainty (landmark_uncertainty.h) and the wireframe's selection rules
// (wireframe_selection.h), each on a hand-built case with its expected figure.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/wireframe_selection.h"
#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::Project;
using testing::TestK;

// A camera at `centre` looking along world +z (identity rotation: x right, y down, z forward).
Pose3 Forward(const Eigen::Vector3d& centre) { return Pose3(Eigen::Matrix3d::Identity(), centre); }

// Rectified stereo, baseline B along x, point at depth Z on the midline: disparity d = f B / Z, each
// view's x off by sigma, so sigma_d = sqrt(2) sigma and sigma_Z = Z^2 / (f B) sqrt(2) sigma, the
// largest axis for Z >> B. The first-order covariance must give it to 2 % (the lateral terms and
// the midline's slight obliquity are below that for Z / B = 20).
TEST(LandmarkUncertaintyTest, PointSigmaIsTheStereoDepthError) {
  const double f = 450, B = 0.2, Z = 4, sigma = 0.3;
  const std::vector<Pose3> cameras = {Forward({-B / 2, 0, 0}), Forward({B / 2, 0, 0})};
  const double expected = Z * Z / (f * B) * std::sqrt(2.0) * sigma;  // 0.0754 m
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, {0, 0, Z}, sigma), expected, 0.02 * expected);
}

TEST(LandmarkUncertaintyTest, PointWithoutBaselineIsUndetermined) {
  const std::vector<Pose3> cameras = {Forward({0, 0, 0}), Forward({0, 0, 0})};
  EXPECT_TRUE(std::isinf(PointPositionSigma(TestK(), cameras, {0.3, 0.1, 4}, 0.3)));
}

// A vertical line (along y) at depth Z seen by the same stereo pair, x taken where it projects in
// the middle of each observed segment (t = 1/2): each image line is off by sigma sqrt(1/4 + 1/4)
// = sigma / sqrt(2) there, so the line's depth error is Z^2 / (f B) sigma. To 2 %.
TEST(LandmarkUncertaintyTest, LineSigmaIsTheStereoDepthErrorOfItsImageLines) {
  const double B = 0.2, Z = 4, sigma = 0.3;
  const Eigen::Matrix3d K = TestK();
  std::vector<LineSegmentView> views;
  for (const double x : {-B / 2, B / 2}) {
    const Pose3 camera = Forward({x, 0, 0});
    views.push_back({camera, Project(K, camera, {0, -0.5, Z}), Project(K, camera, {0, 0.5, Z})});
  }
  const double expected = Z * Z / (450 * B) * sigma;  // 0.0533 m
  EXPECT_NEAR(LinePositionSigma(K, views, {0, 0, Z}, Eigen::Vector3d::UnitY(), sigma), expected,
              0.02 * expected);
  // At the far end (t = 1) the image line is off by sigma: sqrt(2) times more.
  EXPECT_NEAR(LinePositionSigma(K, views, {0, 0.5, Z}, Eigen::Vector3d::UnitY(), sigma), std::sqrt(2.0) * expected,
              0.03 * expected);
}

// A line parallel to the baseline lies in an epipolar plane of the pair: both planes are one, its
// position across them is free.
TEST(LandmarkUncertaintyTest, LineParallelToTheMotionIsUndetermined) {
  const Eigen::Matrix3d K = TestK();
  std::vector<LineSegmentView> views;
  for (const double x : {-0.1, 0.1}) {
    const Pose3 camera = Forward({x, 0, 0});
    views.push_back({camera, Project(K, camera, {-0.5, 0.3, 4}), Project(K, camera, {0.5, 0.3, 4})});
  }
  EXPECT_TRUE(std::isinf(LinePositionSigma(K, views, {0, 0.3, 4}, Eigen::Vector3d::UnitX(), 0.3)));
}

// Pose drift (PoseDrift): the same stereo pair, the second view k = 25 frames after the first, the
// rotations a random walk of 0.0002 rad per axis per frame. The second camera's yaw relative to the
// first is off by 0.0002 sqrt(25) = 0.001 rad, which moves its x by f x 0.001 = 0.45 px (the point
// projects 11 px off the centre: the (1 + x^2 / f^2) factor is 1.0006) and so the disparity: sigma_Z
// = Z^2 / (f B) sqrt(2 sigma^2 + f^2 step^2 k) = 0.110 m, 1.46 times the pixel-only 0.0754 m.
// The first view's own rotation is the common part, left out: frames 100 and 125 give the same.
// A model that let the error average down (independent per view) or took it from frame 0 fails.
TEST(LandmarkUncertaintyTest, PointSigmaAddsTheRelativeRotationDrift) {
  const double f = 450, B = 0.2, Z = 4, sigma = 0.3, step = 0.0002;
  const int k = 25;
  const std::vector<Pose3> cameras = {Forward({-B / 2, 0, 0}), Forward({B / 2, 0, 0})};
  const double expected = Z * Z / (f * B) * std::sqrt(2 * sigma * sigma + f * f * step * step * k);
  const PoseDrift drift{step};
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, {0, 2}, {0, 0, Z}, sigma, PoseDrift()),
              PointPositionSigma(TestK(), cameras, {0, 0, Z}, sigma), 1e-12);
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, {0, k}, {0, 0, Z}, sigma, drift), expected, 0.02 * expected);
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, {100, 100 + k}, {0, 0, Z}, sigma, drift), expected,
              0.02 * expected);
}

// The line of LineSigmaIsTheStereoDepthErrorOfItsImageLines with the same drift: at t = 1/2 each
// image line is off by sigma / sqrt(2) from the pixels, and the second view's yaw moves its image
// line across by f x 0.001 = 0.45 px: sigma_Z = Z^2 / (f B) sqrt(sigma^2 + f^2 step^2 k) = 0.0962 m
// (pixel only 0.0533 m). To 2 %.
TEST(LandmarkUncertaintyTest, LineSigmaAddsTheRelativeRotationDrift) {
  const double f = 450, B = 0.2, Z = 4, sigma = 0.3, step = 0.0002;
  const int k = 25;
  const Eigen::Matrix3d K = TestK();
  std::vector<LineSegmentView> views;
  for (const double x : {-B / 2, B / 2}) {
    const Pose3 camera = Forward({x, 0, 0});
    views.push_back({camera, Project(K, camera, {0, -0.5, Z}), Project(K, camera, {0, 0.5, Z}), x < 0 ? 7 : 7 + k});
  }
  const double expected = Z * Z / (f * B) * std::sqrt(sigma * sigma + f * f * step * step * k);
  EXPECT_NEAR(LinePositionSigma(K, views, {0, 0, Z}, Eigen::Vector3d::UnitY(), sigma, PoseDrift{step}), expected,
              0.02 * expected);
}

// Reference values of the chi-square quantile (any statistics table). Wilson-Hilferty at p = 0.999
// is 3.0 % high for k = 1, 1.7 % for k = 3, 0.6 % for k = 10 (the test is then slightly lenient).
TEST(LandmarkUncertaintyTest, ChiSquareQuantileMatchesTables) {
  EXPECT_NEAR(ChiSquareQuantile(0.999, 1), 10.828, 0.035 * 10.828);
  EXPECT_NEAR(ChiSquareQuantile(0.999, 3), 16.266, 0.02 * 16.266);
  EXPECT_NEAR(ChiSquareQuantile(0.999, 10), 29.588, 0.01 * 29.588);
  EXPECT_NEAR(ChiSquareQuantile(0.99, 4), 13.277, 0.01 * 13.277);
  EXPECT_NEAR(ChiSquareQuantile(0.5, 20), 19.337, 0.005 * 19.337);
}

TEST(LandmarkUncertaintyTest, ChiSquareOfExactObservationsIsZero) {
  const Eigen::Matrix3d K = TestK();
  const std::vector<Pose3> cameras = {Forward({-0.5, 0, 0}), Forward({0, 0, 0}), Forward({0.5, 0, 0})};
  const Eigen::Vector3d point(0.2, -0.1, 3);
  std::vector<Eigen::Vector2d> pixels;
  for (const Pose3& camera : cameras) pixels.push_back(Project(K, camera, point));
  int dof = 0;
  EXPECT_NEAR(PointChiSquare(K, cameras, pixels, point, 0.3, &dof), 0, 1e-12);
  EXPECT_EQ(dof, 3);
  pixels[1].x() += 0.6;  // 2 sigma: chi-square 4
  EXPECT_NEAR(PointChiSquare(K, cameras, pixels, point, 0.3, &dof), 4, 1e-9);
}

// The selection on hand-built landmarks, five cameras 0.25 m apart along x looking along z.
class WireframeSelectionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int i = 0; i < 5; ++i) cameras_.push_back(Forward({0.25 * i, 0, 0}));
  }
  PointLandmark Point(const Eigen::Vector3d& position) const {
    PointLandmark point;
    point.position = position;
    for (int f = 0; f < 5; ++f) point.observations.push_back({f, 0, Project(K_, cameras_[f], position)});
    return point;
  }
  LineLandmark Line(const Eigen::Vector3d& end0, const Eigen::Vector3d& end1, int point_landmark) const {
    LineLandmark line;
    line.point = line.end0 = end0;
    line.end1 = end1;
    line.direction = (end1 - end0).normalized();
    line.point_landmark = point_landmark;
    for (int f = 0; f < 5; ++f) {
      line.observations.push_back({f, 0, 0, Project(K_, cameras_[f], end0), Project(K_, cameras_[f], end1)});
    }
    return line;
  }
  // 40 corners seen with 1 px Gaussian pixel noise (seeded), as in real images.
  Landmarks FortyNoisyCorners() const {
    std::mt19937 random(7);
    std::normal_distribution<double> noise(0.0, 1.0);
    Landmarks landmarks;
    for (int i = 0; i < 40; ++i) {
      landmarks.points.push_back(Point({-1.0 + 0.05 * i, 0.3 - 0.01 * i, 3.0 + 0.05 * i}));
      for (PointObservation& observation : landmarks.points.back().observations) {
        observation.pixel += Eigen::Vector2d(noise(random), noise(random));
      }
    }
    return landmarks;
  }
  const Eigen::Matrix3d K_ = TestK();
  std::vector<Pose3> cameras_;
};

// A point 3 m ahead (parallax 19 degrees over the 1 m path): sigma 3 mm, far below the 1.5-degree
// bound at 3 m (MaxVertexSigma = 0.0216 m). Kept, and its vertical edge too.
TEST_F(WireframeSelectionTest, AWellDeterminedConsistentCornerIsKept) {
  EXPECT_NEAR(MaxVertexSigma(WireframeOptions(), 450, 3), std::sqrt(2.0) * 0.3 / 450 * 3 / std::tan(1.5 * M_PI / 180),
              1e-12);
  Landmarks landmarks;
  landmarks.points.push_back(Point({0.5, 0.2, 3}));
  landmarks.lines.push_back(Line({0.5, 0.2, 3}, {0.5, -0.6, 3}, 0));
  WireframeSelectionReport report;
  const Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, WireframeOptions(), &report);
  ASSERT_EQ(kept.points.size(), 1u);
  ASSERT_EQ(kept.lines.size(), 1u);
  EXPECT_EQ(kept.lines[0].point_landmark, 0);
  EXPECT_EQ(report.points_kept, 1);
  EXPECT_EQ(report.lines_kept, 1);
}

// A wrong track: one of five views sees another corner 2 px away (6.7 sigma). The refined point
// would spread that over all views; here the point stays at the truth, so the statistic is
// (2 / 0.3)^2 = 44 against the 0.999 quantile of chi-square with 7 degrees of freedom (24.3):
// dropped as inconsistent. Its line, whose own end0 is the point projected on it, stays.
TEST_F(WireframeSelectionTest, ATrackThatDoesNotTriangulateConsistentlyIsDropped) {
  Landmarks landmarks;
  landmarks.points.push_back(Point({0.5, 0.2, 3}));
  landmarks.points[0].observations[2].pixel.x() += 2.0;
  landmarks.points.push_back(Point({-0.3, 0.2, 3}));
  landmarks.lines.push_back(Line({0.5, 0.2, 3}, {0.5, -0.6, 3}, 0));
  landmarks.lines.push_back(Line({-0.3, 0.2, 3}, {-0.3, -0.6, 3}, 1));
  WireframeSelectionReport report;
  const Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, WireframeOptions(), &report);
  EXPECT_EQ(report.points_inconsistent, 1);
  ASSERT_EQ(kept.points.size(), 1u);
  EXPECT_EQ(kept.points[0].position, landmarks.points[1].position);
  ASSERT_EQ(kept.lines.size(), 2u);
  EXPECT_EQ(kept.lines[0].point_landmark, -1);  // its point was dropped
  EXPECT_LT((kept.lines[0].end0 - Eigen::Vector3d(0.5, 0.2, 3)).norm(), 1e-9);
  EXPECT_EQ(kept.lines[1].point_landmark, 0);  // renumbered
}

// A corner 60 m ahead, seen over the same 1 m of path: its rays meet at 0.95 degrees, so its
// five-view sigma (3.0 m, mostly depth) is above the bound at 60 m (2.16 m: a two-view point at
// 1.5 degrees). Bundle adjustment can leave such a point behind (it keeps every landmark that
// passes its 1-degree test); the wireframe does not draw it, nor the line from it, whose junction
// end is as uncertain.
TEST_F(WireframeSelectionTest, ADistantLowParallaxCornerIsNotDrawn) {
  Landmarks landmarks;
  landmarks.points.push_back(Point({0.5, 0.2, 60}));
  landmarks.lines.push_back(Line({0.5, 0.2, 60}, {0.5, -2.6, 60}, 0));
  const double sigma = PointPositionSigma(K_, cameras_, {0.5, 0.2, 60}, 0.3);
  EXPECT_NEAR(sigma, 3.0, 0.1);
  EXPECT_NEAR(MaxVertexSigma(WireframeOptions(), 450, 60), 2.16, 0.01);
  WireframeSelectionReport report;
  const Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, WireframeOptions(), &report);
  EXPECT_TRUE(kept.points.empty());
  EXPECT_TRUE(kept.lines.empty());
  EXPECT_EQ(report.points_uncertain, 1);
  EXPECT_EQ(report.lines_uncertain_end0, 1);
}

// A line nearly parallel to the motion (5 degrees off the path, in the cameras' horizontal plane
// shifted 0.3 m down): its planes nearly coincide, its far end is placed by noise. The far end is
// dropped although the junction point is fine; the point stays.
TEST_F(WireframeSelectionTest, ALineNearlyAlongTheMotionIsNotDrawn) {
  Landmarks landmarks;
  const Eigen::Vector3d corner(0.5, 0.3, 3);
  landmarks.points.push_back(Point(corner));
  const Eigen::Vector3d along(std::cos(5 * M_PI / 180), 0.0, std::sin(5 * M_PI / 180));
  landmarks.lines.push_back(Line(corner, corner + 1.0 * along, 0));
  WireframeSelectionReport report;
  const Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, WireframeOptions(), &report);
  EXPECT_EQ(kept.points.size(), 1u);
  EXPECT_TRUE(kept.lines.empty());
  EXPECT_EQ(report.lines_uncertain_end1, 1);
}

// The stored ends were bounded on the poses the line was triangulated with (the odometry) and
// bundle adjustment only slides them onto the refined line, so they keep that pose error along the
// line: here end1 is 0.2 m beyond, and the line's own end0 0.1 m before, what the views see. The
// selection measures the extent again on the final poses (BoundLine's rule: the medians of the
// back-projected ends): both ends at the true corners to 1e-9 m (noise-free views), and the
// direction still from end0 towards end1.
TEST_F(WireframeSelectionTest, LineEndsAreBoundedAgainOnTheFinalPoses) {
  Landmarks landmarks;
  const Eigen::Vector3d top(0.5, 0.2, 3), bottom(0.5, -0.6, 3);
  landmarks.lines.push_back(Line(top, bottom, -1));
  LineLandmark& line = landmarks.lines[0];
  line.end0 = top + 0.1 * Eigen::Vector3d::UnitY();
  line.end1 = bottom - 0.2 * Eigen::Vector3d::UnitY();
  line.point = line.end0;
  WireframeSelectionReport report;
  const Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, WireframeOptions(), &report);
  ASSERT_EQ(kept.lines.size(), 1u);
  EXPECT_LT((kept.lines[0].end0 - top).norm(), 1e-9);
  EXPECT_LT((kept.lines[0].end1 - bottom).norm(), 1e-9);
  EXPECT_GT(kept.lines[0].direction.dot(bottom - top), 0);
  EXPECT_EQ(report.lines_unbounded, 0);
}

// A line whose views disagree on which side of the junction its far end lies: three views end it
// 0.1 m below the corner, two 2 m above. The summed far-minus-near parameters orient it upwards,
// the median far end lies below: no segment of positive length (BoundLine's kNoExtent). Not drawn,
// counted as unbounded; all views lie on one 3D line, so it passes the consistency test first.
TEST_F(WireframeSelectionTest, ALineWithNoExtentOnTheFinalPosesIsNotDrawn) {
  Landmarks landmarks;
  const Eigen::Vector3d top(0.5, 0.2, 3), bottom(0.5, -0.6, 3), down(0, -1, 0);
  landmarks.lines.push_back(Line(top, bottom, -1));
  for (LineObservation& observation : landmarks.lines[0].observations) {
    const Eigen::Vector3d far_end = top + (observation.frame < 3 ? 0.1 : -2.0) * down;
    observation.p1 = Project(K_, cameras_[observation.frame], far_end);
  }
  WireframeSelectionReport report;
  const Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, WireframeOptions(), &report);
  EXPECT_TRUE(kept.lines.empty());
  EXPECT_EQ(report.lines_inconsistent, 0);
  EXPECT_EQ(report.lines_unbounded, 1);
}

// Two views of a line always meet in one: a two-view segment track on two different edges passes
// an empty chi-square test. The same edge seen in views 0 and 4 only, without a junction point, is
// not drawn (untestable); seen in views 0, 2 and 4 (2 degrees of freedom) it is, and in views 0 and
// 4 from a kept corner point (whose test checked the junction correspondence) it is too.
TEST_F(WireframeSelectionTest, ATwoViewLineIsDrawnOnlyFromAKeptPoint) {
  Landmarks landmarks;
  landmarks.points.push_back(Point({0.5, 0.2, 3}));
  landmarks.lines.push_back(Line({0.5, 0.2, 3}, {0.5, -0.6, 3}, -1));
  landmarks.lines.push_back(landmarks.lines[0]);
  landmarks.lines.push_back(Line({0.5, 0.2, 3}, {0.5, -0.6, 3}, 0));
  for (int i : {0, 2}) {
    std::vector<LineObservation>& two = landmarks.lines[i].observations;
    two = {two[0], two[4]};
  }
  std::vector<LineObservation>& three = landmarks.lines[1].observations;
  three = {three[0], three[2], three[4]};
  WireframeSelectionReport report;
  const Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, WireframeOptions(), &report);
  ASSERT_EQ(kept.lines.size(), 2u);
  EXPECT_EQ(kept.lines[0].observations.size(), 3u);
  EXPECT_EQ(kept.lines[1].point_landmark, 0);
  EXPECT_EQ(report.lines_untestable, 1);
}

// Real images: 40 corners seen with 1 px Gaussian noise (seeded) instead of the 0.3 px of rendered
// ones. The estimate is the noise to 10 % (1.4826 x median |component| of 400 samples: its relative
// standard error is about 1.1 / sqrt(400) = 6 %). With it, the chi-square test keeps (nearly) every
// corner; with the fixed 0.3 px floor alone it drops most of them, since (1 / 0.3)^2 x 7 dof is far
// above the 0.999 quantile (24.3).
TEST_F(WireframeSelectionTest, PixelNoiseIsEstimatedFromThePointResiduals) {
  const Landmarks landmarks = FortyNoisyCorners();
  EXPECT_NEAR(EstimatePixelSigma(K_, cameras_, landmarks), 1.0, 0.1);
  WireframeSelectionReport estimated, fixed;
  SelectWireframeLandmarks(K_, cameras_, landmarks, WireframeOptions(), &estimated);
  WireframeOptions fixed_options;
  fixed_options.estimate_pixel_sigma = false;
  SelectWireframeLandmarks(K_, cameras_, landmarks, fixed_options, &fixed);
  EXPECT_NEAR(estimated.pixel_sigma_px, 1.0, 0.1);
  EXPECT_EQ(fixed.pixel_sigma_px, 0.3);
  EXPECT_GE(estimated.points_kept, 38);  // 0.1 % expected to fail at the 0.999 level
  EXPECT_LE(fixed.points_kept, 10);
}

// The selection with drift: a corner 30 m ahead seen by the five cameras (1 m of path) as frames
// 0, 10, 20, 30, 40 (a 60-frame sequence's views of one corner are spread so). Its pixel-only
// sigma (0.76 m) passes the bound at 30 m (1.08 m); with 0.0002 rad per axis per frame of rotation
// drift its last view's rotation relative to the first is off by 0.0013 rad (0.57 px, about twice
// the pixel noise, and correlated, so it does not average down over the views): sigma 1.39 m, not
// drawn. Without drift (pose_rotation_step_rad 0) it is.
// The determination test holds the vertex sigma and its bound to the same pixel noise: with 1 px
// estimated from 40 noisy corners, a noise-free corner 30 m ahead over the 1 m path (sigma / bound
// = 3.0 / 2.16 x 30 / 60 = 0.69 at any noise, drift off) is still drawn. With the bound left at the
// 0.3 px floor it would read 0.69 x 1 / 0.3 = 2.3 and be dropped.
TEST_F(WireframeSelectionTest, DeterminationDoesNotDependOnTheEstimatedNoise) {
  Landmarks landmarks = FortyNoisyCorners();
  landmarks.points.push_back(Point({0.5, 0.2, 30}));
  WireframeOptions options;
  options.pose_rotation_step_rad = 0;
  WireframeSelectionReport report;
  const Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  EXPECT_NEAR(report.pixel_sigma_px, 1.0, 0.1);
  EXPECT_EQ(report.points_uncertain, 0);
  ASSERT_FALSE(kept.points.empty());
  EXPECT_EQ(kept.points.back().position, Eigen::Vector3d(0.5, 0.2, 30));
}

TEST_F(WireframeSelectionTest, RotationDriftAlongThePathMakesAVertexUndetermined) {
  Landmarks landmarks;
  const Eigen::Vector3d corner(0.5, 0.2, 30);
  landmarks.points.push_back(Point(corner));
  for (PointObservation& observation : landmarks.points[0].observations) observation.frame *= 10;
  std::vector<Pose3> cameras(41, cameras_[0]);
  for (int f = 0; f < 5; ++f) cameras[10 * f] = cameras_[f];
  WireframeOptions pixel_only;
  pixel_only.pose_rotation_step_rad = 0;
  const double bound = MaxVertexSigma(pixel_only, 450, 30);
  EXPECT_NEAR(bound, 1.08, 0.01);
  EXPECT_NEAR(PointPositionSigma(K_, cameras_, corner, 0.3), 0.76, 0.01);
  EXPECT_NEAR(PointPositionSigma(K_, cameras_, {0, 10, 20, 30, 40}, corner, 0.3, PoseDrift{0.0002}), 1.39, 0.01);
  WireframeSelectionReport with_drift, without;
  EXPECT_TRUE(SelectWireframeLandmarks(K_, cameras, landmarks, WireframeOptions(), &with_drift).points.empty());
  EXPECT_EQ(with_drift.points_uncertain, 1);
  EXPECT_EQ(SelectWireframeLandmarks(K_, cameras, landmarks, pixel_only, &without).points.size(), 1u);
}

// An accuracy asked of the map (WireframeOptions::tolerance_m), on the five cameras of the fixture
// (1 m of path, the default pose drift): eight corners 3 m ahead (sigma 9.7 mm) and two 8 m and
// 9 m ahead, which pass the depth-relative bound (sigma 6.1 and 7.7 cm against 29 and 32 cm) but
// are each within 5 cm of the truth with probability 1 - exp(-t^2 / (2 sigma^2)) = 0.28 and 0.19
// only; a line leaves the 9 m corner. Predicted share of the 11 vertices within 5 cm: about 0.79.
// Asked 0.9: the least determined vertices go, largest sigma first, with their landmarks (the 9 m
// corner takes its line with it), until the prediction for the rest, (8 + 0.28) / 9 = 0.92, meets
// it; the 8 m corner stays. Without the option, or asked 0.5, all are drawn. The predicted share
// is the Rayleigh formula's to 1e-9 (a one-dimensional Gaussian's gives 0.95).
TEST_F(WireframeSelectionTest, AnAccuracyAskedDropsTheLeastDeterminedVerticesOnly) {
  Landmarks landmarks;
  for (int i = 0; i < 8; ++i) landmarks.points.push_back(Point({-0.5 + 0.25 * i, 0.2, 3}));
  landmarks.points.push_back(Point({0.5, 0.2, 8}));
  landmarks.points.push_back(Point({0.5, 0.2, 9}));
  landmarks.lines.push_back(Line({0.5, 0.2, 9}, {0.5, -1.0, 9}, 9));
  WireframeOptions options;
  WireframeSelectionReport report;
  Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  EXPECT_EQ(kept.points.size(), 10u);
  EXPECT_EQ(kept.lines.size(), 1u);
  EXPECT_EQ(report.predicted_share, 0);  // off

  // The model's figures, computed here from the same sigmas.
  const PoseDrift drift = WireframePoseDrift(options, cameras_);
  const std::vector<int> frames = {0, 1, 2, 3, 4};
  auto within = [](double sigma) { return 1 - std::exp(-0.05 * 0.05 / (2 * sigma * sigma)); };
  const double near = PointPositionSigma(K_, cameras_, frames, {0.5, 0.2, 3}, 0.3, drift);
  const double at8 = PointPositionSigma(K_, cameras_, frames, {0.5, 0.2, 8}, 0.3, drift);
  const double at9 = PointPositionSigma(K_, cameras_, frames, {0.5, 0.2, 9}, 0.3, drift);
  EXPECT_NEAR(near, 0.0097, 0.0005);
  EXPECT_NEAR(at8, 0.0613, 0.0005);
  EXPECT_NEAR(at9, 0.0772, 0.0005);
  EXPECT_LT(at9, MaxVertexSigma(options, 450, 9));  // the relative bound passes it

  options.tolerance_m = 0.05;
  kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  ASSERT_EQ(kept.points.size(), 9u);
  EXPECT_EQ(kept.points[8].position, Eigen::Vector3d(0.5, 0.2, 8));
  EXPECT_TRUE(kept.lines.empty());  // drawn from the dropped corner
  EXPECT_EQ(report.points_beyond_tolerance, 1);
  EXPECT_EQ(report.lines_beyond_tolerance, 1);
  double expected = within(at8);
  for (int i = 0; i < 8; ++i) {
    expected += within(PointPositionSigma(K_, cameras_, frames, landmarks.points[i].position, 0.3, drift));
  }
  EXPECT_NEAR(report.predicted_share, expected / 9, 1e-9);
  EXPECT_GE(report.predicted_share, 0.9);

  // Asked less than the prediction already gives: nothing is dropped.
  options.tolerance_share = 0.5;
  kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  EXPECT_EQ(kept.points.size(), 10u);
  EXPECT_EQ(kept.lines.size(), 1u);
  EXPECT_LT(report.predicted_share, 0.9);
  EXPECT_GT(report.predicted_share, 0.5);
}

// WireframeOptions::far_end_at_point_px. A vertical edge from a drawn corner (point 0) to another
// drawn corner (point 1) 0.8 m below, its observed image segments overshooting the lower corner by
// 0.02 m (3 px at 3 m, f 450): off, end1 is the median back-projected far end, 0.02 m beyond the
// corner (to 1e-9 m); on (1 px across, 5 px along), end1 is point 1's position. A corner 0.02 m
// (3 px) beside the edge's image lines is not taken.
TEST_F(WireframeSelectionTest, AFarEndAtADrawnPointIsThatPoint) {
  const Eigen::Vector3d top(0.5, 0.2, 3), bottom(0.5, -0.6, 3), overshoot(0.5, -0.62, 3);
  Landmarks landmarks;
  landmarks.points.push_back(Point(top));
  landmarks.points.push_back(Point(bottom));
  landmarks.lines.push_back(Line(top, overshoot, 0));
  WireframeOptions options;
  options.far_end_at_point_px = 0;  // off
  WireframeSelectionReport report;
  Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  ASSERT_EQ(kept.lines.size(), 1u);
  EXPECT_LT((kept.lines[0].end1 - overshoot).norm(), 1e-9);
  EXPECT_EQ(report.lines_far_end_at_point, 0);
  options.far_end_at_point_px = 1;
  kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  ASSERT_EQ(kept.lines.size(), 1u);
  EXPECT_EQ(kept.lines[0].end1, bottom);
  EXPECT_EQ(report.lines_far_end_at_point, 1);
  // Beside the image lines: not the edge's end.
  landmarks.points[1] = Point({0.52, -0.6, 3});
  kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  ASSERT_EQ(kept.lines.size(), 1u);
  EXPECT_LT((kept.lines[0].end1 - overshoot).norm(), 1e-9);
  EXPECT_EQ(report.lines_far_end_at_point, 0);
}

// A line's own variance factor (rule 2). Eight vertical edges from drawn corners 3 m ahead whose
// far end-points are observed 0.1 px across their image lines, alternately to either side in the
// five views: chi-square 5 x (0.1 / 0.3)^2 = 0.556 on 6 degrees of freedom, 0.104 of the median of
// chi-square(6) (5.35): the lines' variance of unit weight. A ninth edge from a corner 3 m ahead, 40
// degrees off the cameras' path (its planes spread little): its far end's first-order sigma is 0.81
// of the bound (0.107 m against 0.131 m at 3.64 m). Observed 0.3 px across, alternately (a segment
// switching between the two edges of a double edge), its chi-square is 5, chi2 / dof 0.83: it passes
// the consistency test (22.5 at 0.999) and is drawn without the factor (and would be with a factor
// against the assumed noise alone, which needs chi2 / dof > 1). Against the other lines it is 8.0
// times the unit variance: its sigma times sqrt(8.0) = 2.8 is 2.3 times the bound, not drawn. Observed
// like the others (0.1 px) its factor is below 1, so its first-order sigma stands: drawn.
TEST_F(WireframeSelectionTest, ALineNoisierThanTheOthersGetsALargerSigma) {
  auto shift_far_ends = [](LineLandmark* line, double shift) {
    for (LineObservation& observation : line->observations) {
      const Eigen::Vector2d t = (observation.p1 - observation.p0).normalized();
      observation.p1 += (observation.frame % 2 == 0 ? shift : -shift) * Eigen::Vector2d(-t.y(), t.x());
    }
  };
  Landmarks landmarks;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d top(-0.6 + 0.15 * i, 0.2, 3);
    landmarks.points.push_back(Point(top));
    landmarks.lines.push_back(Line(top, top + Eigen::Vector3d(0, -0.8, 0), i));
    shift_far_ends(&landmarks.lines.back(), 0.1);
  }
  const Eigen::Vector3d corner(0.5, 0.3, 3);
  const Eigen::Vector3d end1 =
      corner + Eigen::Vector3d(std::cos(40 * M_PI / 180), 0.0, std::sin(40 * M_PI / 180));
  landmarks.points.push_back(Point(corner));
  const LineLandmark exact = Line(corner, end1, 8);
  landmarks.lines.push_back(exact);
  shift_far_ends(&landmarks.lines.back(), 0.3);

  auto chi_square_of = [&](const LineLandmark& line, int* dof) {
    std::vector<LineSegmentView> views;
    for (const LineObservation& observation : line.observations) {
      views.push_back({cameras_[observation.frame], observation.p0, observation.p1, observation.frame});
    }
    return LineChiSquare(K_, views, line.point, line.direction, 0.3, dof);
  };
  int dof = 0;
  EXPECT_NEAR(chi_square_of(landmarks.lines[0], &dof), 0.556, 0.01);
  ASSERT_EQ(dof, 6);
  EXPECT_NEAR(ChiSquareQuantile(0.5, 6), 5.35, 0.02);
  EXPECT_NEAR(chi_square_of(landmarks.lines[8], &dof), 5.0, 0.05);
  EXPECT_LT(5.0 / 6, 1.0);
  WireframeOptions options;
  std::vector<LineSegmentView> views;
  for (const LineObservation& observation : landmarks.lines[8].observations) {
    views.push_back({cameras_[observation.frame], observation.p0, observation.p1, observation.frame});
  }
  const double sigma =
      LinePositionSigma(K_, views, end1, exact.direction, 0.3, WireframePoseDrift(options, cameras_), true);
  EXPECT_NEAR(sigma / MaxVertexSigma(options, 450, end1.z()), 0.81, 0.03);

  WireframeSelectionReport report;
  Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  EXPECT_EQ(kept.lines.size(), 8u);  // the eight vertical edges: factor 1
  EXPECT_EQ(report.lines_uncertain_end1, 1);
  EXPECT_EQ(kept.points.size(), 9u);

  landmarks.lines[8] = exact;
  shift_far_ends(&landmarks.lines[8], 0.1);  // as noisy as the others
  kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  EXPECT_EQ(kept.lines.size(), 9u);
}

// A point's own variance factor (rule 2). Eight corners 3 m ahead observed 0.1 px off in x,
// alternately to either side in the five views: chi-square 5 x (0.1 / 0.3)^2 = 0.556 on 7 degrees
// of freedom, 0.0875 of chi-square(7)'s median (6.35): the points' variance of unit weight. A ninth
// corner at a depth where its sigma is 0.82 of the bound (31 m, low parallax over the 1 m path),
// observed 0.3 px off alternately: chi-square 5, chi2 / dof 0.71 (passes, and below 1), 8.2 times
// the unit variance, so its sigma times 2.9 is over the bound: not drawn (its first-order sigma
// alone would be). Observed like the others it is drawn.
TEST_F(WireframeSelectionTest, APointNoisierThanTheOthersGetsALargerSigma) {
  auto shift_pixels = [](PointLandmark* point, double shift) {
    for (PointObservation& observation : point->observations) {
      observation.pixel.x() += observation.frame % 2 == 0 ? shift : -shift;
    }
  };
  Landmarks landmarks;
  for (int i = 0; i < 8; ++i) {
    landmarks.points.push_back(Point({-0.6 + 0.15 * i, 0.2, 3}));
    shift_pixels(&landmarks.points.back(), 0.1);
  }
  const Eigen::Vector3d far(0.5, 0.2, 31);
  landmarks.points.push_back(Point(far));
  shift_pixels(&landmarks.points.back(), 0.3);
  WireframeOptions options;
  const std::vector<int> frames = {0, 1, 2, 3, 4};
  const double sigma =
      PointPositionSigma(K_, cameras_, frames, far, 0.3, WireframePoseDrift(options, cameras_));
  EXPECT_NEAR(sigma / MaxVertexSigma(options, 450, 31), 0.82, 0.03);
  std::vector<Eigen::Vector2d> pixels;
  for (const PointObservation& observation : landmarks.points[8].observations)
    pixels.push_back(observation.pixel);
  int dof = 0;
  EXPECT_NEAR(PointChiSquare(K_, cameras_, pixels, far, 0.3, &dof), 5.0, 0.01);
  ASSERT_EQ(dof, 7);
  EXPECT_NEAR(ChiSquareQuantile(0.5, 7), 6.35, 0.02);

  WireframeSelectionReport report;
  Landmarks kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  EXPECT_EQ(kept.points.size(), 8u);
  EXPECT_EQ(report.points_uncertain, 1);

  landmarks.points[8] = Point(far);
  shift_pixels(&landmarks.points[8], 0.1);  // as noisy as the others
  kept = SelectWireframeLandmarks(K_, cameras_, landmarks, options, &report);
  EXPECT_EQ(kept.points.size(), 9u);
}

TEST(WireframeOptionsTest, BadOptionsAreRejected) {
  WireframeOptions options;
  EXPECT_TRUE(options.Check().ok());
  options.pixel_sigma_px = 0;
  EXPECT_FALSE(options.Check().ok());
  options = WireframeOptions();
  options.consistency_level = 1;
  EXPECT_FALSE(options.Check().ok());
  options = WireframeOptions();
  options.min_equivalent_parallax_deg = 0;
  EXPECT_FALSE(options.Check().ok());
  options = WireframeOptions();
  options.pose_rotation_step_rad = -1e-4;
  EXPECT_FALSE(options.Check().ok());
  options = WireframeOptions();
  options.tolerance_m = -0.05;
  EXPECT_FALSE(options.Check().ok());
  options = WireframeOptions();
  options.tolerance_share = 1;
  EXPECT_FALSE(options.Check().ok());
  options = WireframeOptions();
  options.far_end_at_point_px = -1;
  EXPECT_FALSE(options.Check().ok());
  options = WireframeOptions();
  options.far_end_along_px = 0;
  EXPECT_FALSE(options.Check().ok());
  options = WireframeOptions();
  options.line_end_along_sigma = 3;
  EXPECT_FALSE(options.Check().ok());
  options.line_end_along_sigma = -1;
  EXPECT_FALSE(options.Check().ok());
}

}  // namespace
}  // namespace sfm
