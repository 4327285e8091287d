// The plane-noise correction of the line vertex sigma (LinePositionSigma's subtract_plane_noise,
// WireframeOptions::line_sigma_subtracts_plane_noise): docs/tracks_and_triangulation.md, "Plane
// noise in the line sigma".
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/line_triangulation.h"
#include "backend/triangulation/wireframe_selection.h"
#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::Project;
using testing::TestK;

// A camera at `centre` looking along world +z (identity rotation: x right, y down, z forward).
Pose3 Forward(const Eigen::Vector3d& centre) { return Pose3(Eigen::Matrix3d::Identity(), centre); }

// Six cameras moving forward along z, 0.2 m apart (the corridors' step), and a 0.15 m edge across
// the path 0.1 m below the plane y = 0 that holds the path (an edge near the camera's height, 5 m
// ahead): every view's plane nearly contains the path, so the edge's position across them is poorly
// determined. Its image is 13-17 px long. Its true far-end sigma at 0.3 px (noise-free views, the
// true direction) is 0.71 m, five times the wireframe's bound there (0.14 m at 3.9 m depth).
struct CoplanarEdge {
  std::vector<Pose3> cameras;
  Eigen::Vector3d a{0.3, 0.1, 5}, b{0.45, 0.1, 5};
  CoplanarEdge() {
    for (int k = 0; k < 6; ++k) cameras.push_back(Forward({0, 0, 0.2 * k}));
  }
  // The views with each end-point moved across the segment by independent noise of sigma px.
  std::vector<LineSegmentView> NoisyViews(std::mt19937& random, double sigma) const {
    std::normal_distribution<double> noise(0, sigma);
    std::vector<LineSegmentView> views;
    for (size_t k = 0; k < cameras.size(); ++k) {
      const Eigen::Vector2d p0 = Project(TestK(), cameras[k], a), p1 = Project(TestK(), cameras[k], b);
      const Eigen::Vector2d normal = Eigen::Vector2d(-(p1 - p0).y(), (p1 - p0).x()).normalized();
      views.push_back(
          {cameras[k], p0 + noise(random) * normal, p1 + noise(random) * normal, static_cast<int>(k)});
    }
    return views;
  }
};

// The determination test on the noisy estimate of that edge, 2000 seeded trials at 0.3 px: the far
// end's sigma at the least-squares line (IntersectPlanes), against the wireframe's bound
// (MaxVertexSigma, 1.5 degrees) at its smallest depth. Without the correction the noisy planes'
// spread makes nearly every estimate look determined (measured 1961 of 2000); with it about a
// quarter still do (539: the corrected information is unbiased, not noise-free). Stated: above 0.9
// without, below 0.35 with. Fails without the correction.
TEST(WireframePlaneNoiseTest, ACoplanarEdgeIsUndeterminedDespiteItsNoisyPlanes) {
  const CoplanarEdge edge;
  const Eigen::Matrix3d K = TestK();
  const WireframeOptions options;
  std::mt19937 random(7);
  const int trials = 2000;
  int passed_without = 0, passed_with = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const std::vector<LineSegmentView> views = edge.NoisyViews(random, 0.3);
    std::vector<Eigen::Vector4d> planes;
    for (const LineSegmentView& view : views)
      planes.push_back(BackProjectedPlane(K, {view.world_T_camera, view.p0, view.p1}));
    const Line3 line = IntersectPlanes(planes, Eigen::Vector3d(0, 0, 0.5));
    // The estimate's point nearest the true far end stands for its far end.
    const Eigen::Vector3d end1 = line.point + (edge.b - line.point).dot(line.direction) * line.direction;
    double depth = std::numeric_limits<double>::infinity();
    for (const Pose3& camera : edge.cameras) depth = std::min(depth, (camera.Inverse() * end1).z());
    if (!(depth > 0)) continue;
    const double bound = MaxVertexSigma(options, K(0, 0), depth);
    if (LinePositionSigma(K, views, end1, line.direction, 0.3) <= bound) ++passed_without;
    if (LinePositionSigma(K, views, end1, line.direction, 0.3, PoseDrift(), true) <= bound) ++passed_with;
  }
  EXPECT_GT(passed_without, 0.9 * trials);
  EXPECT_LT(passed_with, 0.35 * trials);
}

// A well-determined line changes little: a door post (vertical, 1 m long at 4 m, 112 px) seen from
// the same six forward-moving cameras 1 m to its side, no noise in the observations. The normals'
// noise (about 0.004 rad a view) against their spread (about 0.07 rad) takes (0.004 / 0.07)^2,
// under 1 %, of the information: the sigma grows by less than 1 % (measured 0.014 %).
TEST(WireframePlaneNoiseTest, AWellDeterminedLineKeepsItsSigma) {
  const Eigen::Matrix3d K = TestK();
  std::vector<LineSegmentView> views;
  const Eigen::Vector3d a(1, -0.5, 4), b(1, 0.5, 4);
  for (int k = 0; k < 6; ++k) {
    const Pose3 camera = Forward({0, 0, 0.2 * k});
    views.push_back({camera, Project(K, camera, a), Project(K, camera, b), k});
  }
  const double plain = LinePositionSigma(K, views, b, Eigen::Vector3d::UnitY(), 0.3);
  const double corrected = LinePositionSigma(K, views, b, Eigen::Vector3d::UnitY(), 0.3, PoseDrift(), true);
  ASSERT_TRUE(std::isfinite(plain));
  EXPECT_GE(corrected, plain);
  EXPECT_LT(corrected, 1.01 * plain);
}

// Through the pipeline's path: the noisy view sets of the coplanar edge that TriangulateLine accepts
// with its defaults (planes more than 3 degrees apart, centres spread, residuals under 4 px) and
// BoundLine bounds, as line landmarks given to SelectWireframeLandmarks (no pose drift, 0.3 px).
// Without the correction nearly all of them are drawn (measured 516 of 560); with it a fifth are
// (117): stated above 0.8 and below 0.3. Fails without the correction. The along-the-line rule
// (line_end_along_sigma) is off here, to test the correction alone: on, it drops every
// one of these estimates even without the correction (their noisy directions run into depth, so
// their own end0 is seen nearly end-on; measured 0 of 448 drawn).
TEST(WireframePlaneNoiseTest, TheSelectionDropsMostNoisyEstimatesOfACoplanarEdge) {
  const CoplanarEdge edge;
  const Eigen::Matrix3d K = TestK();
  std::mt19937 random(11);
  WireframeOptions off;
  off.line_end_along_sigma = 0;
  off.line_sigma_subtracts_plane_noise = false;
  off.pose_rotation_step_rad = 0;
  off.pose_translation_step_fraction = 0;
  off.estimate_pixel_sigma = false;
  WireframeOptions on = off;
  on.line_sigma_subtracts_plane_noise = true;
  int triangulated = 0, kept_off = 0, kept_on = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const std::vector<LineSegmentView> views = edge.NoisyViews(random, 0.3);
    std::vector<LineView> line_views;
    LineLandmark line;
    for (const LineSegmentView& view : views) {
      line_views.push_back({view.world_T_camera, view.p0, view.p1});
      line.observations.push_back({view.frame, 0, 0, view.p0, view.p1});
    }
    Line3 estimate;
    Segment3 segment;
    const LineTriangulationOptions triangulation;
    if (TriangulateLine(K, line_views, triangulation, &estimate) != LineStatus::kOk ||
        BoundLine(K, line_views, estimate, nullptr, triangulation, &segment) != LineStatus::kOk) {
      continue;
    }
    ++triangulated;
    line.point = estimate.point;
    line.direction = estimate.direction;
    line.end0 = segment.end0;
    line.end1 = segment.end1;
    Landmarks landmarks;
    landmarks.lines.push_back(line);
    kept_off += static_cast<int>(SelectWireframeLandmarks(K, edge.cameras, landmarks, off).lines.size());
    kept_on += static_cast<int>(SelectWireframeLandmarks(K, edge.cameras, landmarks, on).lines.size());
  }
  ASSERT_GT(triangulated, 100);
  EXPECT_GT(kept_off, 0.8 * triangulated);
  EXPECT_LT(kept_on, 0.3 * triangulated);
}

}  // namespace
}  // namespace sfm
