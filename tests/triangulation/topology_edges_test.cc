// AddTopologyEdges on a hand-built scene seen by five cameras driving along x: which joins become
// wireframe edges, which are refused and why, the split at a point on an edge and the line
// landmark it makes a duplicate of.
#include "backend/triangulation/topology_edges.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::ForwardCameras;
using testing::Project;
using testing::TestK;

// The scene's points, by name, and which pairs the images show joined: `shared` pairs use one
// detected line segment in the frames listed (every frame when empty).
struct Scene {
  std::vector<Eigen::Vector3d> points;
  struct Join {
    int a, b;
    std::set<int> frames;  // empty: all
  };
  std::vector<Join> joins;
};

enum Point { kA, kB, kC, kM, kD, kE, kG };

Scene DoorwayScene() {
  Scene scene;
  scene.points = {
      {4, -1, 0.5},    // A: threshold's left end
      {4, 1, 0.5},     // B: threshold's right end (A-B across the motion)
      {4, 1, 2},       // C: above B (B-C vertical)
      {4, 0, 0.5},     // M: on A-B, a junction that uses another image segment (a T's stem)
      {3, -1, 2.2},    // D: a ceiling line along the motion, D-E
      {6, -1, 2.2},    // E
      {9, -0.5, 1.6},  // G: in the epipolar plane of D-E but off its line: joined to E in every image
  };
  scene.joins = {{kA, kB, {}}, {kB, kC, {}}, {kD, kE, {}}, {kE, kG, {}}, {kC, kD, {0}}};
  return scene;
}

// Junctions per frame (junction j is point j) and the drawn landmarks observing them.
void MakeObservations(const Scene& scene, const std::vector<Pose3>& cameras,
                      std::vector<Junctions>* junctions, Landmarks* landmarks) {
  const Eigen::Matrix3d K = TestK();
  junctions->assign(cameras.size(), Junctions());
  landmarks->points.clear();
  for (size_t p = 0; p < scene.points.size(); ++p) {
    PointLandmark point;
    point.track_id = static_cast<int>(p);
    point.position = scene.points[p];
    landmarks->points.push_back(point);
  }
  for (size_t f = 0; f < cameras.size(); ++f) {
    for (size_t p = 0; p < scene.points.size(); ++p) {
      Junction junction;
      junction.id = static_cast<int>(p);
      junction.location = Project(K, cameras[f], scene.points[p]);
      // A short stub of its own, so that every junction has a segment that joins nothing.
      junction.segments.push_back({junction.location + Eigen::Vector2d(0, 30), 1000 + static_cast<int>(p)});
      (*junctions)[f].push_back(junction);
      landmarks->points[p].observations.push_back(
          {static_cast<int>(f), static_cast<int>(p), junction.location});
    }
    for (size_t k = 0; k < scene.joins.size(); ++k) {
      const Scene::Join& join = scene.joins[k];
      if (!join.frames.empty() && !join.frames.count(static_cast<int>(f))) continue;
      Junction& a = (*junctions)[f][join.a];
      Junction& b = (*junctions)[f][join.b];
      a.segments.push_back({b.location, static_cast<int>(k)});
      b.segments.push_back({a.location, static_cast<int>(k)});
    }
  }
}

// Figures protected: the kept edges exactly (A-M, M-B, B-C, D-E), and the counts of candidates (5),
// refused as unsupported (C-D: joined in one of the five frames that see both, 1), refused as
// undetermined (E-G: in an epipolar plane, 10.6 degrees off the baseline, 1), splits (M, 1) and
// line landmarks dropped (the one along A-B, 1; the one up from C is kept).
TEST(AddTopologyEdges, KeepsSupportedPlacedJoinsSplitsAndDropsDuplicateLines) {
  const std::vector<Pose3> cameras = ForwardCameras();
  const Scene scene = DoorwayScene();
  std::vector<Junctions> junctions;
  Landmarks landmarks;
  MakeObservations(scene, cameras, &junctions, &landmarks);
  LineLandmark along_ab;
  along_ab.point_landmark = kA;
  along_ab.end0 = scene.points[kA];
  along_ab.end1 = Eigen::Vector3d(4, 0.97, 0.5);
  LineLandmark up_from_c;
  up_from_c.point_landmark = kC;
  up_from_c.end0 = scene.points[kC];
  up_from_c.end1 = Eigen::Vector3d(4, 1, 2.5);
  landmarks.lines = {along_ab, up_from_c};

  TopologyEdgeReport report;
  AddTopologyEdges(cameras, junctions, TopologyEdgeOptions(), &landmarks, &report);
  const std::vector<std::pair<int, int>> expected = {{kA, kM}, {kB, kC}, {kB, kM}, {kD, kE}};
  EXPECT_EQ(landmarks.point_edges, expected);
  EXPECT_EQ(report.candidates, 5);
  EXPECT_EQ(report.unsupported, 1);
  EXPECT_EQ(report.undetermined, 1);
  EXPECT_EQ(report.splits, 1);
  EXPECT_EQ(report.edges, 4);
  EXPECT_EQ(report.lines_dropped, 1);
  ASSERT_EQ(landmarks.lines.size(), 1u);
  EXPECT_EQ(landmarks.lines[0].point_landmark, kC);
}

// min_support 0.2 takes C-D (joined in one of five frames); with its join in no frame it is no
// candidate at all.
TEST(AddTopologyEdges, MinSupportIsTheShareOfFramesSeeingBothEnds) {
  const std::vector<Pose3> cameras = ForwardCameras();
  Scene scene = DoorwayScene();
  std::vector<Junctions> junctions;
  Landmarks landmarks;
  MakeObservations(scene, cameras, &junctions, &landmarks);
  TopologyEdgeOptions options;
  options.min_support = 0.2;
  TopologyEdgeReport report;
  AddTopologyEdges(cameras, junctions, options, &landmarks, &report);
  EXPECT_EQ(report.unsupported, 0);
  EXPECT_EQ(std::count(landmarks.point_edges.begin(), landmarks.point_edges.end(),
                       std::make_pair(static_cast<int>(kC), static_cast<int>(kD))),
            1);

  scene.joins.pop_back();
  MakeObservations(scene, cameras, &junctions, &landmarks);
  AddTopologyEdges(cameras, junctions, options, &landmarks, &report);
  EXPECT_EQ(report.candidates, 4);
}

// Junction segments that are separate detections but collinear and pointing at each other join the
// junctions when they leave less than max_gap_px between them, not when the gap is wider.
TEST(AddTopologyEdges, CollinearSegmentsJoinWithinTheEndPointAllowance) {
  const std::vector<Pose3> cameras = ForwardCameras();
  Scene scene = DoorwayScene();
  std::vector<Junctions> junctions;
  Landmarks landmarks;
  MakeObservations(scene, cameras, &junctions, &landmarks);
  // In frames 1-4, A and B see each other through two collinear segments with a gap in the middle
  // (the shared segment of A-B is replaced).
  for (const double gap_px : {8.0, 14.0}) {
    MakeObservations(scene, cameras, &junctions, &landmarks);
    for (int f = 1; f < 5; ++f) {
      Junction& a = junctions[f][kA];
      Junction& b = junctions[f][kB];
      const Eigen::Vector2d u = (b.location - a.location).normalized();
      const double half = 0.5 * ((b.location - a.location).norm() - gap_px);
      for (JunctionSegment& segment : a.segments) {
        if (segment.line_segment == 0) segment = {a.location + half * u, 2000};
      }
      for (JunctionSegment& segment : b.segments) {
        if (segment.line_segment == 0) segment = {b.location - half * u, 2001};
      }
    }
    TopologyEdgeReport report;
    AddTopologyEdges(cameras, junctions, TopologyEdgeOptions(), &landmarks, &report);
    const bool kept = std::count(landmarks.point_edges.begin(), landmarks.point_edges.end(),
                                 std::make_pair(static_cast<int>(kA), static_cast<int>(kM))) == 1;
    EXPECT_EQ(kept, gap_px < TopologyEdgeOptions().max_gap_px) << "gap " << gap_px << " px";
  }
}

}  // namespace
}  // namespace sfm
