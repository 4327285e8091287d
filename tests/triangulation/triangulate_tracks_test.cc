#include "backend/triangulation/triangulate_tracks.h"

#include <gtest/gtest.h>

#include <vector>

#include "frontend/tracks/tracks.h"
#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::LineAngle;
using testing::LookAt;
using testing::Project;
using testing::TestK;

struct Scene {
  std::vector<Pose3> cameras;
  std::vector<Junctions> frames;
  std::vector<JunctionTrack> tracks;
};

// A corner at `corner` with arms to `ends`, seen by five cameras driving along x; frame k stores
// arm a as segment (a + k) % N, so the matches between frames k and k + d have shift d % N.
void AddCorner(const Eigen::Vector3d& corner, const std::vector<Eigen::Vector3d>& ends, Scene* scene) {
  const int n = static_cast<int>(ends.size());
  for (size_t k = 0; k < scene->cameras.size(); ++k) {
    Junction junction;
    junction.id = static_cast<int>(scene->frames[k].size());
    junction.location = Project(TestK(), scene->cameras[k], corner);
    junction.segments.resize(n);
    for (int a = 0; a < n; ++a) {
      junction.segments[(a + k) % n].end = Project(TestK(), scene->cameras[k], ends[a]);
    }
    scene->frames[k].push_back(junction);
  }
}

Scene MakeScene(const Eigen::Vector3d& corner, const std::vector<Eigen::Vector3d>& ends,
                const Eigen::Vector3d& far_corner, const std::vector<Eigen::Vector3d>& far_ends) {
  Scene scene;
  for (int k = 0; k < 5; ++k)
    scene.cameras.push_back(LookAt(Eigen::Vector3d(0.4 * k, 0, 1), Eigen::Vector3d(10, 0, 1)));
  scene.frames.resize(5);
  AddCorner(corner, ends, &scene);
  AddCorner(far_corner, far_ends, &scene);
  std::vector<FramePairMatches> pairs;
  for (const auto& [a, b] : FramePairsToMatch(5)) {
    pairs.push_back({a, b, {{0, 0, 0.9, (b - a) % 3}, {1, 1, 0.8, (b - a) % 2}}});
  }
  scene.tracks = BuildTracks(scene.frames, pairs);
  return scene;
}

// A wall's top corner 5 m ahead on the left: an edge along the motion (unobservable), one down
// and one across. A second corner 80 m ahead: too little parallax for its point, and its two
// edges' planes nearly coincide.
const Eigen::Vector3d kCorner(5, 1.5, 1.8);
const std::vector<Eigen::Vector3d> kCornerEnds = {kCorner + Eigen::Vector3d(1.5, 0, 0),
                                                  kCorner + Eigen::Vector3d(0, 0, -1.2),
                                                  kCorner + Eigen::Vector3d(0, -0.8, 0)};
Scene WallCornerScene() {
  const Eigen::Vector3d far_corner(80, -2, 2);
  return MakeScene(kCorner, kCornerEnds, far_corner,
                   {far_corner + Eigen::Vector3d(0, 0, -1), far_corner + Eigen::Vector3d(0, 1, 0)});
}

TEST(TriangulateTracksTest, MakesPointsAndBoundedLinesAndCountsTheFailures) {
  const Eigen::Vector3d& corner = kCorner;
  const std::vector<Eigen::Vector3d>& ends = kCornerEnds;
  const Scene scene = WallCornerScene();
  ASSERT_EQ(scene.tracks.size(), 2u);

  TriangulationReport report;
  const Landmarks landmarks =
      TriangulateTracks(TestK(), scene.cameras, scene.frames, scene.tracks, TriangulationOptions(), &report);
  EXPECT_EQ(report.point_status, (std::vector<PointStatus>{PointStatus::kOk, PointStatus::kLowParallax}));
  EXPECT_EQ(report.line_status[0],
            (std::vector<LineStatus>{LineStatus::kUnobservable, LineStatus::kOk, LineStatus::kOk}));
  EXPECT_EQ(report.line_status[1],
            (std::vector<LineStatus>{LineStatus::kUnobservable, LineStatus::kUnobservable}));
  EXPECT_EQ(report.Count(PointStatus::kOk), 1);
  EXPECT_EQ(report.Count(PointStatus::kLowParallax), 1);
  EXPECT_EQ(report.Count(LineStatus::kOk), 2);
  EXPECT_EQ(report.Count(LineStatus::kUnobservable), 3);

  ASSERT_EQ(landmarks.points.size(), 1u);
  const PointLandmark& point = landmarks.points[0];
  EXPECT_EQ(point.track_id, 0);
  EXPECT_LT((point.position - corner).norm(), 1e-9);
  ASSERT_EQ(point.observations.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(point.observations[k].frame, k);
    EXPECT_EQ(point.observations[k].junction, 0);
    EXPECT_EQ(point.observations[k].pixel, scene.frames[k][0].location);
  }

  // The two observable edges, arms 1 and 2 in track segment order, from the corner point.
  ASSERT_EQ(landmarks.lines.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    const int arm = i + 1;
    const LineLandmark& line = landmarks.lines[i];
    EXPECT_EQ(line.point_landmark, 0);
    EXPECT_LT((line.end0 - corner).norm(), 1e-9);
    EXPECT_LT((line.end1 - ends[arm]).norm(), 1e-9);
    EXPECT_LT((line.point - corner).norm(), 1e-9);
    EXPECT_LT(LineAngle(line.direction, ends[arm] - corner), 1e-9);
    EXPECT_GT(line.direction.dot(ends[arm] - corner), 0);
    ASSERT_EQ(line.observations.size(), 5u);
    for (int k = 0; k < 5; ++k) {
      const LineObservation& observation = line.observations[k];
      EXPECT_EQ(observation.frame, k);
      EXPECT_EQ(observation.junction, 0);
      EXPECT_EQ(observation.segment, (arm + k) % 3);
      EXPECT_EQ(observation.p0, scene.frames[k][0].location);
      EXPECT_EQ(observation.p1, scene.frames[k][0].segments[(arm + k) % 3].end);
    }
  }
}

// A view without the segment (-1 in TrackView::segments: a partial match, an L in frame 2 where the
// other frames see the corner's three arms) is left out of that segment track's line; the line
// comes from the other four views, as exactly as from all five (1e-9 m).
TEST(TriangulateTracksTest, AViewWithoutTheSegmentIsLeftOutOfItsLine) {
  const Eigen::Vector3d corner(5, 1.5, 1.8);
  const std::vector<Eigen::Vector3d> ends = {corner + Eigen::Vector3d(1.5, 0, 0),
                                             corner + Eigen::Vector3d(0, 0, -1.2),
                                             corner + Eigen::Vector3d(0, -0.8, 0)};
  const Eigen::Vector3d far_corner(80, -2, 2);
  Scene scene = MakeScene(corner, ends, far_corner,
                          {far_corner + Eigen::Vector3d(0, 0, -1), far_corner + Eigen::Vector3d(0, 1, 0)});
  ASSERT_EQ(scene.tracks[0].NumSegments(), 3);
  scene.tracks[0].views[2].segments[2] = -1;
  const Landmarks landmarks =
      TriangulateTracks(TestK(), scene.cameras, scene.frames, scene.tracks, TriangulationOptions());
  ASSERT_EQ(landmarks.lines.size(), 2u);
  EXPECT_EQ(landmarks.lines[0].observations.size(), 5u);
  const LineLandmark& line = landmarks.lines[1];
  EXPECT_LT((line.end1 - ends[2]).norm(), 1e-9);
  ASSERT_EQ(line.observations.size(), 4u);
  for (const LineObservation& observation : line.observations) EXPECT_NE(observation.frame, 2);
}

TEST(TriangulateTracksTest, NoTrackNoLandmark) {
  TriangulationReport report;
  const Landmarks landmarks =
      TriangulateTracks(TestK(), {Pose3()}, {Junctions()}, {}, TriangulationOptions(), &report);
  EXPECT_TRUE(landmarks.points.empty());
  EXPECT_TRUE(landmarks.lines.empty());
  EXPECT_TRUE(report.point_status.empty());
}

// WallCornerScene on poses that drifted (the last two cameras turned 1 and 2 degrees about the
// vertical, as an odometry's heading drifts): the near corner's rays 8-16 px apart fail its track
// with kLargeReprojectionError (bound 4 px); the far one fails too. TriangulateMissingPoints on
// the true poses adds the near point (within 1e-9 m, with its five observations), not the far one
// (low parallax on any poses); a second call adds nothing, the track having its point.
TEST(TriangulateMissingPointsTest, AddsThePointsOfTracksThatFailedOnDriftedPoses) {
  const Scene scene = WallCornerScene();
  std::vector<Pose3> drifted = scene.cameras;
  for (int k = 3; k < 5; ++k) {
    const double yaw = (k - 2) * 3.14159265358979323846 / 180;
    drifted[k].rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) * drifted[k].rotation;
  }
  TriangulationReport report;
  Landmarks landmarks =
      TriangulateTracks(TestK(), drifted, scene.frames, scene.tracks, TriangulationOptions(), &report);
  ASSERT_EQ(report.point_status.size(), 2u);
  EXPECT_EQ(report.point_status[0], PointStatus::kLargeReprojectionError);
  EXPECT_NE(report.point_status[1], PointStatus::kOk);  // behind a turned camera
  ASSERT_TRUE(landmarks.points.empty());

  const PointTriangulationOptions options = TriangulationOptions().point;
  EXPECT_EQ(TriangulateMissingPoints(TestK(), scene.cameras, scene.frames, scene.tracks, options, &landmarks), 1);
  ASSERT_EQ(landmarks.points.size(), 1u);
  EXPECT_EQ(landmarks.points[0].track_id, scene.tracks[0].id);
  EXPECT_LT((landmarks.points[0].position - kCorner).norm(), 1e-9);
  EXPECT_EQ(landmarks.points[0].observations.size(), 5u);
  EXPECT_EQ(TriangulateMissingPoints(TestK(), scene.cameras, scene.frames, scene.tracks, options, &landmarks), 0);
  EXPECT_EQ(landmarks.points.size(), 1u);
}

}  // namespace
}  // namespace sfm
