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

}  // namespace
}  // namespace sfm
