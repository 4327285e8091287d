// Joining the landmarks of a second triangulation to the adjusted ones (landmark_merge.h).
#include "backend/triangulation/landmark_merge.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

PointLandmark Point(int track, double x) {
  PointLandmark point;
  point.track_id = track;
  point.position = Eigen::Vector3d(x, 0, 0);
  point.observations = {{0, track, {1, 1}}, {1, track, {2, 2}}};
  return point;
}

// A line seen as segment `segment` of junction `junction` in frames `frames`.
LineLandmark Line(int point_landmark, int junction, int segment, std::initializer_list<int> frames,
                  double y) {
  LineLandmark line;
  line.point = Eigen::Vector3d(0, y, 0);
  line.direction = Eigen::Vector3d::UnitZ();
  line.end0 = line.point;
  line.end1 = line.point + line.direction;
  line.point_landmark = point_landmark;
  for (int frame : frames) line.observations.push_back({frame, junction, segment, {1, 1}, {3, 3}});
  return line;
}

// The adjusted map: points of tracks 0 and 2, a line of track 0's junction 10 segment 1 in frames
// 0 and 1. The second triangulation: points of tracks 0-3 (elsewhere: x + 100), and four lines:
// the same segment track seen in frames 0 and 2 (it shares (0, 10, 1): known), segment 0 of track
// 0's junction (new, its point already in the map), a line of track 3 (new, its point new) and one
// without a point.
Landmarks Adjusted() {
  Landmarks landmarks;
  landmarks.points = {Point(0, 1), Point(2, 2)};
  landmarks.lines = {Line(0, 10, 1, {0, 1}, 1)};
  return landmarks;
}
Landmarks Retriangulated() {
  Landmarks landmarks;
  landmarks.points = {Point(0, 101), Point(1, 102), Point(2, 103), Point(3, 104)};
  landmarks.lines = {Line(0, 10, 1, {0, 2}, 11), Line(0, 10, 0, {0, 1}, 12), Line(3, 13, 0, {3, 4}, 13),
                     Line(-1, 14, 2, {5, 6}, 14)};
  return landmarks;
}

// What it protects: the adjusted landmarks stay as they are (the re-triangulated copies of their
// tracks are not added twice), new tracks' landmarks are appended in order, and a new line's
// point_landmark indexes its track's point in the joined map, with end0 on that point.
TEST(MergeRetriangulatedLandmarksTest, AddsOnlyTracksWithoutALandmark) {
  Landmarks landmarks = Adjusted();
  LandmarkMergeReport report;
  MergeRetriangulatedLandmarks(Retriangulated(), RetriangulatedLandmarks::kAddNew, &landmarks, &report);
  ASSERT_EQ(landmarks.points.size(), 4u);
  EXPECT_EQ(landmarks.points[0].position.x(), 1);  // kept, not the re-triangulated 101
  EXPECT_EQ(landmarks.points[1].position.x(), 2);
  EXPECT_EQ(landmarks.points[2].track_id, 1);
  EXPECT_EQ(landmarks.points[2].position.x(), 102);
  EXPECT_EQ(landmarks.points[3].track_id, 3);
  ASSERT_EQ(landmarks.lines.size(), 4u);
  EXPECT_EQ(landmarks.lines[0].point.y(), 1);  // kept
  EXPECT_EQ(landmarks.lines[0].observations.size(), 2u);
  EXPECT_EQ(landmarks.lines[1].point.y(), 12);
  EXPECT_EQ(landmarks.lines[1].point_landmark, 0);                     // track 0's adjusted point
  EXPECT_EQ(landmarks.lines[1].end0, landmarks.points[0].position);    // moved onto it
  EXPECT_EQ(landmarks.lines[2].point_landmark, 3);                     // track 3's new point
  EXPECT_EQ(landmarks.lines[2].end0, Retriangulated().lines[2].end0);  // its own, unchanged
  EXPECT_EQ(landmarks.lines[3].point_landmark, -1);
  EXPECT_EQ(report.points_added, 2);
  EXPECT_EQ(report.lines_added, 3);
  EXPECT_EQ(report.lines_linked_to_existing_point, 1);
}

TEST(MergeRetriangulatedLandmarksTest, ReplaceTakesTheSecondTriangulation) {
  Landmarks landmarks = Adjusted();
  LandmarkMergeReport report;
  MergeRetriangulatedLandmarks(Retriangulated(), RetriangulatedLandmarks::kReplace, &landmarks, &report);
  ASSERT_EQ(landmarks.points.size(), 4u);
  EXPECT_EQ(landmarks.points[0].position.x(), 101);
  ASSERT_EQ(landmarks.lines.size(), 4u);
  EXPECT_EQ(landmarks.lines[0].point.y(), 11);
  EXPECT_EQ(report.points_added, 4);
  EXPECT_EQ(report.lines_added, 4);
}

TEST(MergeRetriangulatedLandmarksTest, NothingNewChangesNothing) {
  Landmarks landmarks = Adjusted();
  Landmarks same = Adjusted();
  MergeRetriangulatedLandmarks(same, RetriangulatedLandmarks::kAddNew, &landmarks);
  EXPECT_EQ(landmarks.points.size(), 2u);
  EXPECT_EQ(landmarks.lines.size(), 1u);
}

}  // namespace
}  // namespace sfm
