// AgreeLinesAndPoints on a hand-built scene seen by five cameras driving along x: a 3D line across
// the motion whose observed segment stops 3 cm short of the drawn point at its far end, a point on
// the line 4 mm off it, and two points whose junctions use the line's image segment but do not
// agree with the 3D line (10 cm off it; 0.6 m beyond its end).
#include "backend/triangulation/line_point_agreement.h"

#include <gtest/gtest.h>

#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::DistanceToLine;
using testing::ForwardCameras;
using testing::Project;
using testing::TestK;

enum Point { kA, kB, kM, kN, kF };

struct Scene {
  std::vector<Pose3> cameras = ForwardCameras();
  std::vector<Junctions> junctions;
  Landmarks landmarks;
};

// Line A -> B along y at x = 4 m, z = 0.5 m, from A's junction; its observed far end (the detected
// segment's end) at y = 0.97 m. Every junction uses detected segment 0; each also has a stub of its
// own. Observations are exact projections.
Scene MakeScene() {
  Scene scene;
  const Eigen::Matrix3d K = TestK();
  const std::vector<Eigen::Vector3d> positions = {
      {4, -1, 0.5},   // A: the line's junction point
      {4, 1, 0.503},  // B: the far end, 3 mm above the line
      {4, 0, 0.504},  // M: on the line, 4 mm above it
      {4, 0.5, 0.6},  // N: 10 cm above the line
      {4, 1.6, 0.5},  // F: on the line's extension, 0.6 m beyond B
  };
  const Eigen::Vector3d observed_end(4, 0.97, 0.5);
  for (size_t p = 0; p < positions.size(); ++p) {
    PointLandmark point;
    point.track_id = static_cast<int>(p);
    point.position = positions[p];
    scene.landmarks.points.push_back(point);
  }
  LineLandmark line;
  line.point = positions[kA];
  line.direction = Eigen::Vector3d::UnitY();
  line.end0 = positions[kA];
  line.end1 = observed_end;
  line.point_landmark = kA;
  for (size_t f = 0; f < scene.cameras.size(); ++f) {
    Junctions frame;
    for (size_t p = 0; p < positions.size(); ++p) {
      Junction junction;
      junction.id = static_cast<int>(p);
      junction.location = Project(K, scene.cameras[f], positions[p]);
      junction.segments.push_back({junction.location + Eigen::Vector2d(0, 30), 100 + static_cast<int>(p)});
      frame.push_back(junction);
      scene.landmarks.points[p].observations.push_back(
          {static_cast<int>(f), static_cast<int>(p), junction.location});
    }
    const Eigen::Vector2d end = Project(K, scene.cameras[f], observed_end);
    frame[kA].segments.push_back({end, 0});
    for (int p : {kB, kM, kN, kF}) frame[p].segments.push_back({frame[kA].location, 0});
    line.observations.push_back({static_cast<int>(f), kA, 1, frame[kA].location, end});
    scene.junctions.push_back(frame);
  }
  scene.landmarks.lines.push_back(line);
  return scene;
}

// Figures protected: B becomes the line's far end (end1_point B, end1 at B's final position to
// 1e-12 m): it lies 3 mm across the line (within the 0.999 chi-square bound of the point's and the
// line's covariances) and its projections 4-6 px beyond the observed far end-points (under the 11 px
// gap); it is fused with the line, to between 0.5 and 2.5 mm off it. M (4 mm off) splits the line
// and is fused with it, to between 1 and 3 mm off (2.1 mm). N (10 cm off) and F (0.6 m, some 60
// px, beyond the end) stay where they are and are neither end nor split. Counts: 4 candidates, 1
// end, 2 points fused, 1 split.
TEST(AgreeLinesAndPoints, SnapsTheFarEndAndFusesAPointOnTheLine) {
  Scene scene = MakeScene();
  const Landmarks before = scene.landmarks;
  LinePointAgreementReport report;
  AgreeLinesAndPoints(TestK(), scene.cameras, scene.junctions, LinePointAgreementOptions(), &scene.landmarks,
                      &report);
  const LineLandmark& line = scene.landmarks.lines[0];
  EXPECT_EQ(line.end1_point, kB);
  EXPECT_LT((line.end1 - scene.landmarks.points[kB].position).norm(), 1e-12);
  ASSERT_EQ(line.interior_points.size(), 1u);
  EXPECT_EQ(line.interior_points[0], kM);
  const Eigen::Vector3d a = before.points[kA].position;
  const double m_before = DistanceToLine(before.points[kM].position, a, Eigen::Vector3d::UnitY());
  const double m_after = DistanceToLine(scene.landmarks.points[kM].position, a, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(m_before, 0.004, 1e-12);
  EXPECT_LT(m_after, 0.003);
  EXPECT_GT(m_after, 0.001);
  const double b_after = DistanceToLine(scene.landmarks.points[kB].position, a, Eigen::Vector3d::UnitY());
  EXPECT_LT(b_after, 0.0025);
  EXPECT_GT(b_after, 0.0005);
  for (int p : {kA, kN, kF})
    EXPECT_EQ(scene.landmarks.points[p].position, before.points[p].position) << "point " << p;
  EXPECT_EQ(report.candidates, 4);
  EXPECT_EQ(report.ends_at_points, 1);
  EXPECT_EQ(report.points_on_lines, 2);
  EXPECT_EQ(report.splits, 1);
}

// Without the image evidence (no junction of B, M, N or F uses the line's detected segment)
// nothing changes, however close the points lie.
TEST(AgreeLinesAndPoints, NeedsTheJunctionsToShareTheImageSegment) {
  Scene scene = MakeScene();
  for (Junctions& frame : scene.junctions) {
    for (int p : {kB, kM, kN, kF}) frame[p].segments.back().line_segment = 7;
  }
  const Landmarks before = scene.landmarks;
  LinePointAgreementReport report;
  AgreeLinesAndPoints(TestK(), scene.cameras, scene.junctions, LinePointAgreementOptions(), &scene.landmarks,
                      &report);
  EXPECT_EQ(report.candidates, 0);
  EXPECT_EQ(scene.landmarks.lines[0].end1_point, -1);
  EXPECT_TRUE(scene.landmarks.lines[0].interior_points.empty());
  EXPECT_EQ(scene.landmarks.lines[0].end1, before.lines[0].end1);
  EXPECT_EQ(scene.landmarks.points[kM].position, before.points[kM].position);
}

}  // namespace
}  // namespace sfm
