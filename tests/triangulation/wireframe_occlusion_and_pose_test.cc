// The pose drift's translation part (landmark_uncertainty.h) and the wireframe selection's
// occlusion-candidate rule (wireframe_selection.h), each on a hand-built case with its figure.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/point_triangulation.h"
#include "backend/triangulation/triangulation_options.h"
#include "backend/triangulation/wireframe_selection.h"
#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::Project;
using testing::TestK;

Pose3 Forward(const Eigen::Vector3d& centre) { return Pose3(Eigen::Matrix3d::Identity(), centre); }

// Translation drift (PoseDrift::translation_step_m): the rectified stereo pair of
// PointSigmaAddsTheRelativeRotationDrift (wireframe_selection_test.cc), the second view k = 25
// frames after the first, the camera centres a random walk of 0.0006 m per axis per frame. The
// second centre relative to the first is off by 0.0006 sqrt(25) = 0.003 m along the baseline, which
// moves the point's x in that view by f 0.003 / Z = 0.3375 px (its offsets along y and z move the
// disparity by B / (2 Z) = 1/40 of that or not at all): sigma_Z = Z^2 / (f B) sqrt(2 sigma^2 +
// (f step / Z)^2 k) = 0.0964 m, against 0.0754 m from the pixels alone. To 2 %. The first view's
// centre is the common part, left out: frames 100 and 125 give the same. Fails without the
// translation term (0.0754) or with the error taken from frame 0 (0.0754 -> 0.24 m at frames
// 100, 125).
TEST(PoseDriftTest, PointSigmaAddsTheRelativeTranslationDrift) {
  const double f = 450, B = 0.2, Z = 4, sigma = 0.3, step = 0.0006;
  const int k = 25;
  const std::vector<Pose3> cameras = {Forward({-B / 2, 0, 0}), Forward({B / 2, 0, 0})};
  const double shift_px = f * step / Z;
  const double expected = Z * Z / (f * B) * std::sqrt(2 * sigma * sigma + shift_px * shift_px * k);
  PoseDrift drift;
  drift.translation_step_m = step;
  EXPECT_NEAR(expected, 0.0964, 0.0001);
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, {0, k}, {0, 0, Z}, sigma, drift), expected,
              0.02 * expected);
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, {100, 100 + k}, {0, 0, Z}, sigma, drift), expected,
              0.02 * expected);
}

// The vertical line of LineSigmaAddsTheRelativeRotationDrift with the same translation drift: at
// t = 1/2 each image line is off by sigma / sqrt(2) from its end-points, and the second centre's
// 0.003 m along the baseline moves its image line across itself by 0.3375 px: sigma_Z = Z^2 / (f B)
// sqrt(sigma^2 + (f step / Z)^2 k) = 0.0803 m (pixels alone 0.0533 m). To 2 %. Rotation and
// translation drift add as independent variances: both together give sqrt(0.0803^2 + 0.0962^2 -
// 0.0533^2).
TEST(PoseDriftTest, LineSigmaAddsTheRelativeTranslationDrift) {
  const double f = 450, B = 0.2, Z = 4, sigma = 0.3, step = 0.0006, rotation_step = 0.0002;
  const int k = 25;
  const Eigen::Matrix3d K = TestK();
  std::vector<LineSegmentView> views;
  for (const double x : {-B / 2, B / 2}) {
    const Pose3 camera = Forward({x, 0, 0});
    views.push_back(
        {camera, Project(K, camera, {0, -0.5, Z}), Project(K, camera, {0, 0.5, Z}), x < 0 ? 3 : 3 + k});
  }
  const double shift_px = f * step / Z;
  const double translation = Z * Z / (f * B) * std::sqrt(sigma * sigma + shift_px * shift_px * k);
  const double rotation =
      Z * Z / (f * B) * std::sqrt(sigma * sigma + f * f * rotation_step * rotation_step * k);
  const double pixels = Z * Z / (f * B) * sigma;
  EXPECT_NEAR(translation, 0.0803, 0.0001);
  PoseDrift drift;
  drift.translation_step_m = step;
  EXPECT_NEAR(LinePositionSigma(K, views, {0, 0, Z}, Eigen::Vector3d::UnitY(), sigma, drift), translation,
              0.02 * translation);
  drift.rotation_step_rad = rotation_step;
  const double both = std::sqrt(translation * translation + rotation * rotation - pixels * pixels);
  EXPECT_NEAR(LinePositionSigma(K, views, {0, 0, Z}, Eigen::Vector3d::UnitY(), sigma, drift), both,
              0.02 * both);
}

// The selection's translation step is the option's fraction of the median camera step, so a scene in
// other units (here x 10) or a robot twice as fast gets the same rule: cameras 0.25 m apart with one
// 5 m jump (the median ignores it) give 0.003 x 0.25 = 0.00075 m, the same cameras x 10 give 0.0075.
// Fails with a fixed step in metres (0.0006 for both).
TEST(PoseDriftTest, TranslationStepScalesWithTheCameraSteps) {
  std::vector<Pose3> cameras;
  for (const double x : {0.0, 0.25, 0.5, 0.75, 5.75}) cameras.push_back(Forward({x, 0, 0}));
  WireframeOptions options;
  EXPECT_NEAR(WireframePoseDrift(options, cameras).translation_step_m, 0.00075, 1e-12);
  EXPECT_EQ(WireframePoseDrift(options, cameras).rotation_step_rad, options.pose_rotation_step_rad);
  for (Pose3& camera : cameras) camera.translation *= 10;
  EXPECT_NEAR(WireframePoseDrift(options, cameras).translation_step_m, 0.0075, 1e-12);
  EXPECT_EQ(WireframePoseDrift(options, {cameras[0]}).translation_step_m, 0);
}

TEST(PoseDriftTest, BadTranslationStepIsRejected) {
  WireframeOptions options;
  options.pose_translation_step_fraction = -1e-4;
  EXPECT_FALSE(options.Check().ok());
  options.pose_translation_step_fraction = std::nan("");
  EXPECT_FALSE(options.Check().ok());
}

// Why a T or X needs three views. Two views test a point with one degree of freedom, the epipolar
// constraint: a location that slides along the epipolar line between the views (as an occlusion's
// does when the edges' images run along it) leaves the statistic at 0 and moves the point along
// its ray. Here a corner 4 m ahead of a 0.2 m stereo baseline (epipolar lines: image rows) is seen
// 3 px further right in the second view: statistic 0 (exactly: the rays still meet), depth now
// f B / (d + 3) = 3.74 m, 0.26 m off. A third view on the same baseline (0.2 m further) transfers
// the depth from the other two: the same 3 px slide in the middle view gives a statistic of
// 3^2 x 2/3 / 0.3^2 = 67 against the 0.999 quantile with 3 degrees of freedom (16.3, Wilson-Hilferty
// 16.6): caught.
TEST(OcclusionCandidateTest, TwoViewsCannotSeeASlideAlongTheEpipolarLine) {
  const Eigen::Matrix3d K = TestK();
  const double f = 450, B = 0.2, Z = 4, slide = 3;
  const Eigen::Vector3d corner(0, 0, Z);
  const std::vector<Pose3> two = {Forward({0, 0, 0}), Forward({B, 0, 0})};
  std::vector<PointView> views;
  for (const Pose3& camera : two) views.push_back({camera, Project(K, camera, corner)});
  views[1].pixel.x() -= slide;  // the second view sees the point moving right-to-left: more disparity
  Eigen::Vector3d x;
  ASSERT_EQ(TriangulatePoint(K, views, PointTriangulationOptions(), &x), PointStatus::kOk);
  int dof = 0;
  EXPECT_NEAR(PointChiSquare(K, two, {views[0].pixel, views[1].pixel}, x, 0.3, &dof), 0, 1e-6);
  EXPECT_EQ(dof, 1);
  const double disparity = f * B / Z;  // 22.5 px
  EXPECT_NEAR(x.z(), f * B / (disparity + slide), 1e-6);
  EXPECT_GT((x - corner).norm(), 0.25);

  const std::vector<Pose3> three = {Forward({0, 0, 0}), Forward({B, 0, 0}), Forward({2 * B, 0, 0})};
  std::vector<Eigen::Vector2d> pixels;
  for (const Pose3& camera : three) pixels.push_back(Project(K, camera, corner));
  pixels[1].x() -= slide;
  std::vector<PointView> three_views;
  for (int i = 0; i < 3; ++i) three_views.push_back({three[i], pixels[i]});
  const Eigen::Vector3d refined = RefinePoint(K, three_views, corner, 20);
  const double statistic = PointChiSquare(K, three, pixels, refined, 0.3, &dof);
  EXPECT_EQ(dof, 3);
  EXPECT_NEAR(statistic, slide * slide * 2.0 / 3.0 / 0.09, 0.05 * 66.7);
  EXPECT_GT(statistic, ChiSquareQuantile(0.999, 3));
}

// The rule in the selection: five cameras 0.25 m apart along x, corners 3 m ahead (sigma 3 mm, far
// below the bound). A point whose junction is a T (or an X) in any view is drawn only with three
// views or more; the same two-view point is drawn when its junction is an L, when the types are
// not given (the overload without junctions), and with occlusion_candidate_min_views = 2. Its
// two-view line goes with it (a two-view line needs a kept point).
TEST(OcclusionCandidateTest, ATwoViewTOrXIsNotDrawn) {
  const Eigen::Matrix3d K = TestK();
  std::vector<Pose3> cameras;
  for (int i = 0; i < 5; ++i) cameras.push_back(Forward({0.25 * i, 0, 0}));
  // Frame f has junction j = corner j; corner 0 is a T in frame 1 only, corner 1 an L, corner 2 an X.
  const std::vector<Eigen::Vector3d> corners = {{0.5, 0.2, 3}, {-0.3, 0.2, 3}, {0.9, -0.4, 3.5}};
  std::vector<Junctions> junctions(5, Junctions(3));
  junctions[1][0].type = JunctionType::kT;
  for (Junctions& frame : junctions) frame[2].type = JunctionType::kX;
  Landmarks landmarks;
  for (int j = 0; j < 3; ++j) {
    PointLandmark point;
    point.position = corners[j];
    for (int f : {0, 1}) point.observations.push_back({f, j, Project(K, cameras[f], corners[j])});
    landmarks.points.push_back(point);
    LineLandmark line;
    line.point = line.end0 = corners[j];
    line.end1 = corners[j] + Eigen::Vector3d(0, -0.8, 0);
    line.direction = Eigen::Vector3d(0, -1, 0);
    line.point_landmark = j;
    for (int f : {0, 1}) {
      line.observations.push_back(
          {f, j, 0, Project(K, cameras[f], line.end0), Project(K, cameras[f], line.end1)});
    }
    landmarks.lines.push_back(line);
  }
  WireframeSelectionReport report;
  Landmarks kept = SelectWireframeLandmarks(K, cameras, landmarks, junctions, WireframeOptions(), &report);
  EXPECT_EQ(report.points_occlusion_untested, 2);
  ASSERT_EQ(kept.points.size(), 1u);
  EXPECT_EQ(kept.points[0].position, corners[1]);
  ASSERT_EQ(kept.lines.size(), 1u);
  EXPECT_EQ(kept.lines[0].point_landmark, 0);
  EXPECT_EQ(report.lines_untestable, 2);

  EXPECT_EQ(SelectWireframeLandmarks(K, cameras, landmarks, WireframeOptions()).points.size(), 3u);
  WireframeOptions two_views;
  two_views.occlusion_candidate_min_views = 2;
  EXPECT_EQ(SelectWireframeLandmarks(K, cameras, landmarks, junctions, two_views).points.size(), 3u);

  // Seen in a third view, the T and the X are tested with 3 degrees of freedom and drawn.
  for (int j = 0; j < 3; ++j)
    landmarks.points[j].observations.push_back({4, j, Project(K, cameras[4], corners[j])});
  kept = SelectWireframeLandmarks(K, cameras, landmarks, junctions, WireframeOptions(), &report);
  EXPECT_EQ(report.points_occlusion_untested, 0);
  EXPECT_EQ(kept.points.size(), 3u);
}

// MarkOcclusionCandidates: a point seen as a T or an X in any one view is marked, an L seen as an L
// everywhere is not (and a stale mark is cleared).
TEST(OcclusionCandidateTest, PointsSeenAsTOrXAreMarked) {
  std::vector<Junctions> junctions(3, Junctions(3));  // every junction an L by default
  junctions[1][1].type = JunctionType::kT;
  junctions[2][2].type = JunctionType::kX;
  Landmarks landmarks;
  auto add = [&](std::vector<std::pair<int, int>> seen) {
    PointLandmark point;
    for (const auto& [frame, junction] : seen) point.observations.push_back({frame, junction, Eigen::Vector2d::Zero()});
    point.occlusion_candidate = true;  // stale: must be recomputed
    landmarks.points.push_back(point);
  };
  add({{0, 0}, {1, 0}, {2, 0}});  // L, L, L
  add({{0, 1}, {1, 1}});          // L, T
  add({{1, 2}, {2, 2}});          // L, X
  MarkOcclusionCandidates(junctions, &landmarks);
  EXPECT_FALSE(landmarks.points[0].occlusion_candidate);
  EXPECT_TRUE(landmarks.points[1].occlusion_candidate);
  EXPECT_TRUE(landmarks.points[2].occlusion_candidate);
}

TEST(OcclusionCandidateTest, BadOptionsAreRejected) {
  WireframeOptions options;
  options.occlusion_candidate_min_views = 1;
  EXPECT_FALSE(options.Check().ok());
}

}  // namespace
}  // namespace sfm
