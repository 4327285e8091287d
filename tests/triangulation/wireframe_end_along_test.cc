// A back-projected line end's sigma along the line (LineEndAlongSigma,
// WireframeOptions::line_end_along_sigma): docs/tracks_and_triangulation.md, "A line end's position
// along the line".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/wireframe_selection.h"
#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::Project;
using testing::TestK;

// Six cameras looking along world +z (x right, y down), 0.2 m apart along z and weaving 0.3 m
// across (x = -0.15, +0.15, ...), as a robot weaving down a corridor: a line along the corridor
// then has planes that meet.
std::vector<Pose3> WeavingCameras(double weave = 0.15) {
  std::vector<Pose3> cameras;
  for (int k = 0; k < 6; ++k) {
    cameras.push_back(
        Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(k % 2 == 0 ? -weave : weave, 0, 0.2 * k)));
  }
  return cameras;
}

// The point of the line (x, u) nearest the ray from the camera centre through `pixel`.
double BackProjectedAlong(const Eigen::Matrix3d& K, const Pose3& camera, const Eigen::Vector2d& pixel,
                          const Eigen::Vector3d& x, const Eigen::Vector3d& u) {
  const Eigen::Vector3d c = camera.translation;
  const Eigen::Vector3d r = (camera.rotation * (K.inverse() * pixel.homogeneous())).normalized();
  // Minimise |x + s u - c - l r|: the normal equations of (s, l).
  const Eigen::Vector3d w = x - c;
  const double b = u.dot(r), d = u.dot(w), e = r.dot(w);
  return (b * e - d) / (1 - b * b);
}

// An edge along the corridor, 9 degrees off the cameras' axis in the horizontal plane, 0.4 m below
// them, its end 4 m ahead: the rays meet it at 5.8-8.1 degrees (nearly end-on). 4000 seeded trials
// of the two errors the back-projected end carries: the whole line shifted across itself (isotropic,
// 1 cm in each direction, the line's own sigma) and each view's end pixel moved along its image
// line by 0.3 px; the end is the median over the views of the back-projected points (BoundLine's
// rule). The RMS slide along the line is 0.079 m measured, 7.9 times the line's sigma (stated: 7.9
// +- 0.4), and the first-order sigma is within 10 % of it (0.076 m; stated). Fails if the line's
// error is left out (0.006 m) or taken as averaged down over the six views.
TEST(LineEndAlongSigmaTest, AnEndSeenNearlyEndOnSlidesAlongItsLine) {
  const Eigen::Matrix3d K = TestK();
  const std::vector<Pose3> cameras = WeavingCameras();
  const Eigen::Vector3d u = Eigen::Vector3d(std::sin(9 * M_PI / 180), 0, std::cos(9 * M_PI / 180));
  const Eigen::Vector3d x(0.6, 0.4, 4);
  const double across = 0.01, sigma_px = 0.3;
  std::vector<LineSegmentView> views;
  for (size_t k = 0; k < cameras.size(); ++k) {
    views.push_back(
        {cameras[k], Project(K, cameras[k], x), Project(K, cameras[k], x + u), static_cast<int>(k)});
  }
  const double predicted = LineEndAlongSigma(K, views, x, u, sigma_px, across);

  const Eigen::Vector3d a = u.unitOrthogonal(), b = u.cross(a);
  std::mt19937 random(11);
  std::normal_distribution<double> normal(0, 1);
  const int trials = 4000;
  double sum_squares = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Vector3d shifted = x + across * (normal(random) * a + normal(random) * b);
    std::vector<double> along;
    for (const LineSegmentView& view : views) {
      const Eigen::Vector2d t = (view.p1 - view.p0).normalized();
      const Eigen::Vector2d pixel = view.p0 + sigma_px * normal(random) * t;
      along.push_back(BackProjectedAlong(K, view.world_T_camera, pixel, shifted, u));
    }
    std::nth_element(along.begin(), along.begin() + along.size() / 2, along.end());
    // The median of six: the mean of the middle two.
    const double upper = along[along.size() / 2];
    const double lower = *std::max_element(along.begin(), along.begin() + along.size() / 2);
    const double end = 0.5 * (upper + lower);
    sum_squares += end * end;
  }
  const double measured = std::sqrt(sum_squares / trials);
  EXPECT_NEAR(measured / across, 7.9, 0.4);
  EXPECT_NEAR(predicted / measured, 1.0, 0.10);
}

// Seen square-on the along sigma is no larger than the across one: a vertical post's end 4 m ahead.
TEST(LineEndAlongSigmaTest, AnEndSeenAcrossStaysWithinItsAcrossSigma) {
  const Eigen::Matrix3d K = TestK();
  const std::vector<Pose3> cameras = WeavingCameras();
  const Eigen::Vector3d u = -Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x(0.6, 0.4, 4);
  std::vector<LineSegmentView> views;
  for (size_t k = 0; k < cameras.size(); ++k) {
    views.push_back(
        {cameras[k], Project(K, cameras[k], x), Project(K, cameras[k], x + u), static_cast<int>(k)});
  }
  EXPECT_LT(LineEndAlongSigma(K, views, x, u, 0.3, 0.01), 0.01);
}

// The selection with the rule (WireframeOptions::line_end_along_sigma = 1), cameras weaving 0.1 m: a
// line without a junction point, 3 degrees off the cameras' axis, 0.4 m below them, its own end0 5
// m ahead, which the rays meet at 5.3-7.0 degrees. Its across sigma at end0 is 0.019 m (drift and
// plane noise included), well within rule 2's bound at 4 m of depth (0.144 m): drawn without the
// rule. Along the line its sigma is 0.172 m, above the bound: not drawn with it. A post from the
// same end (seen across: along 0.010 m, across 0.110 m) is drawn either way. Fails without the
// along term in the selection.
TEST(LineEndAlongSigmaTest, TheSelectionDropsAnOwnEndSeenEndOn) {
  const Eigen::Matrix3d K = TestK();
  const std::vector<Pose3> cameras = WeavingCameras(0.05);
  auto line_of = [&](const Eigen::Vector3d& end0, const Eigen::Vector3d& end1) {
    LineLandmark line;
    line.point = line.end0 = end0;
    line.end1 = end1;
    line.direction = (end1 - end0).normalized();
    for (int f = 0; f < static_cast<int>(cameras.size()); ++f) {
      line.observations.push_back({f, 0, 0, Project(K, cameras[f], end0), Project(K, cameras[f], end1)});
    }
    return line;
  };
  const Eigen::Vector3d u = Eigen::Vector3d(std::sin(3 * M_PI / 180), 0, std::cos(3 * M_PI / 180));
  Landmarks landmarks;
  landmarks.lines.push_back(line_of({0.5, 0.4, 5}, Eigen::Vector3d(0.5, 0.4, 5) + 1.0 * u));  // end-on
  landmarks.lines.push_back(line_of({0.5, 0.4, 5}, {0.5, -0.6, 5}));                          // a post
  WireframeOptions options;
  EXPECT_EQ(options.line_end_along_sigma, 1);  // the default
  options.line_end_along_sigma = 0;
  WireframeSelectionReport report;
  Landmarks kept = SelectWireframeLandmarks(K, cameras, landmarks, options, &report);
  EXPECT_EQ(kept.lines.size(), 2u);
  options.line_end_along_sigma = 1;
  kept = SelectWireframeLandmarks(K, cameras, landmarks, options, &report);
  ASSERT_EQ(kept.lines.size(), 1u);
  EXPECT_EQ(report.lines_uncertain_end0, 1);
  EXPECT_LT((kept.lines[0].end1 - Eigen::Vector3d(0.5, -0.6, 5)).norm(), 1e-9);
}

// Value 2 holds the far end to the same rule: the same end-on line drawn from a kept corner (so
// only its far end, 6 m ahead, is tested): across sigma 0.023 m, along 0.258 m, bound 0.180 m (at
// 5 m of depth). Drawn with values 0 and 1, not with 2. Fails if value 2 leaves end1 alone.
TEST(LineEndAlongSigmaTest, ValueTwoTestsTheFarEndToo) {
  const Eigen::Matrix3d K = TestK();
  const std::vector<Pose3> cameras = WeavingCameras(0.05);
  const Eigen::Vector3d corner(0.5, 0.4, 5);
  const Eigen::Vector3d u = Eigen::Vector3d(std::sin(3 * M_PI / 180), 0, std::cos(3 * M_PI / 180));
  const Eigen::Vector3d end1 = corner + 1.0 * u;
  Landmarks landmarks;
  PointLandmark point;
  point.position = corner;
  LineLandmark line;
  line.point = line.end0 = corner;
  line.end1 = end1;
  line.direction = u;
  line.point_landmark = 0;
  std::vector<LineSegmentView> views;
  for (int f = 0; f < static_cast<int>(cameras.size()); ++f) {
    point.observations.push_back({f, 0, Project(K, cameras[f], corner)});
    line.observations.push_back({f, 0, 0, Project(K, cameras[f], corner), Project(K, cameras[f], end1)});
    views.push_back({cameras[f], Project(K, cameras[f], corner), Project(K, cameras[f], end1), f});
  }
  landmarks.points.push_back(point);
  landmarks.lines.push_back(line);
  WireframeOptions options;
  const double across = LinePositionSigma(K, views, end1, u, 0.3, WireframePoseDrift(options, cameras), true);
  const double bound = MaxVertexSigma(options, 450, end1.z() - 1.0);
  EXPECT_NEAR(across, 0.023, 0.001);  // well within the bound
  EXPECT_NEAR(bound, 0.180, 0.001);
  EXPECT_NEAR(LineEndAlongSigma(K, views, end1, u, 0.3, across), 0.258, 0.002);  // beyond it
  WireframeSelectionReport report;
  for (int value : {0, 1}) {
    options.line_end_along_sigma = value;
    EXPECT_EQ(SelectWireframeLandmarks(K, cameras, landmarks, options, &report).lines.size(), 1u);
  }
  options.line_end_along_sigma = 2;
  const Landmarks kept = SelectWireframeLandmarks(K, cameras, landmarks, options, &report);
  EXPECT_EQ(kept.lines.size(), 0u);
  EXPECT_EQ(kept.points.size(), 1u);
  EXPECT_EQ(report.lines_uncertain_end1, 1);
}

}  // namespace
}  // namespace sfm
