// MeasureLineCompleteness on hand-built lines and edges.
#include "benchmarks/vgg_lines/line_completeness.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

// A true line of length 2 along x; an edge 0.05 away covering x in [0, 1]: the samples every 0.1
// at x = 0..1 (11 of 21) are within 0.1, the rest beyond it (x = 1.1 is 0.112 from the edge's end).
TEST(LineCompletenessTest, HalfALineCoveredByAnEdge) {
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> lines = {
      {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0)}};
  const std::vector<Eigen::Vector3d> vertices = {Eigen::Vector3d(0, 0.05, 0), Eigen::Vector3d(1, 0.05, 0)};
  const LineCompleteness result = MeasureLineCompleteness(lines, vertices, {{0, 1}}, 0.1, 0.1);
  EXPECT_DOUBLE_EQ(result.true_length, 2);
  EXPECT_NEAR(result.Share(), 11.0 / 21, 1e-12);
  // No edges: nothing is within.
  EXPECT_EQ(MeasureLineCompleteness(lines, vertices, {}, 0.1, 0.1).Share(), 0);
}

// A true line from (-1, 0, 4) to (1, 0, 4) seen by two cameras at the origin and at x = 0.5 (f 100,
// 200 x 200 px, principal point (100, 100)): in camera 1 it runs from u = 75 to 125, in camera 2
// from 62.5 to 112.5, both inside. Camera 1 has a segment over u in [100, 125], camera 2 one over
// [50, 100]: the samples with x in [0, 0.5] (world) are detected in both (u in [100, 112.5] in 1 and
// [87.5, 100] in 2), a quarter of the line: 6 of 21 samples at a step of 0.1 (x = 0, 0.1, .., 0.5).
TEST(LineImageSupportTest, DetectedWhereBothViewsHaveASegment) {
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> lines = {
      {Eigen::Vector3d(-1, 0, 4), Eigen::Vector3d(1, 0, 4)}};
  LineSupportView view;
  view.K << 100, 0, 100, 0, 100, 100, 0, 0, 1;
  view.width = view.height = 200;
  std::vector<LineSupportView> views(2, view);
  views[1].t = Eigen::Vector3d(-0.5, 0, 0);
  views[0].segments = {{Eigen::Vector2d(100, 100), Eigen::Vector2d(125, 100)}};
  views[1].segments = {{Eigen::Vector2d(50, 100.5), Eigen::Vector2d(100, 100.5)}};
  const LineImageSupport support = MeasureLineImageSupport(lines, views, 1.0, 0.1, 2);
  EXPECT_DOUBLE_EQ(support.true_length, 2);
  EXPECT_NEAR(support.visible_length, 2, 1e-12);
  EXPECT_NEAR(support.detected_length, 2.0 * 6 / 21, 1e-12);
  // A segment 1.5 px off the line is not within 1 px: nothing is detected in camera 2, so nothing twice.
  views[1].segments = {{Eigen::Vector2d(50, 101.5), Eigen::Vector2d(100, 101.5)}};
  EXPECT_EQ(MeasureLineImageSupport(lines, views, 1.0, 0.1, 2).detected_length, 0);
}

}  // namespace
}  // namespace sfm
