#include "benchmarks/evaluation/segment_evaluation.h"

#include <fstream>

#include <gtest/gtest.h>

#include "tests/test_data.h"
#include "tests/test_segments.h"

namespace sfm {
namespace {

using testing::Segment;

TEST(SegmentEvaluationTest, CoverageIsTheUnionOfCompatibleDetections) {
  const LineSegments truth = {Segment(0, 0, 100, 0)};
  const LineSegments detected = {
      Segment(-5, 0.5, 40, 0.5),     // covers [0, 40]
      Segment(30, -1, 70, -1),       // overlaps it: union [0, 70]
      Segment(75, 3, 100, 3),        // too far from the line
      Segment(80, 0, 100, 10),       // too steep
      Segment(85, 0, 95, 0),         // covers [85, 95]
  };
  const std::vector<TrueSegmentResult> results = EvaluateEachSegment(detected, truth, SegmentEvaluationOptions());
  EXPECT_NEAR(results[0].coverage, 0.80, 1e-9);
  EXPECT_EQ(results[0].match, -1);  // the best single detection covers 40% < 50%
}

// Only the part of a slightly tilted detection within max_distance of the line counts.
TEST(SegmentEvaluationTest, ClipsATiltedDetectionToTheBand) {
  const LineSegments truth = {Segment(0, 0, 100, 0)};
  const LineSegments detected = {Segment(0, -1, 100, 3)};  // within 1.5 px for x in [0, 62.5]
  const std::vector<TrueSegmentResult> results = EvaluateEachSegment(detected, truth, SegmentEvaluationOptions());
  EXPECT_NEAR(results[0].coverage, 0.625, 1e-3);
}

// End-point offsets follow eq. (8): detected minus true along the outward direction.
TEST(SegmentEvaluationTest, EndpointOffsetsUseTheOutwardSign) {
  const LineSegments truth = {Segment(10, 0, 110, 0)};
  const LineSegments detected = {Segment(112, 0.2, 14, -0.2)};  // reversed; 4 px short, 2 px long
  const std::vector<TrueSegmentResult> results = EvaluateEachSegment(detected, truth, SegmentEvaluationOptions());
  ASSERT_EQ(results[0].match, 0);
  EXPECT_NEAR(results[0].endpoint_t[0], -4, 1e-9);
  EXPECT_NEAR(results[0].endpoint_t[1], 2, 1e-9);
  EXPECT_NEAR(results[0].endpoint_error[0], std::hypot(4, 0.2), 1e-9);
  const SegmentEvaluation pooled = EvaluateSegments(detected, truth, SegmentEvaluationOptions());
  EXPECT_EQ(pooled.num_covered, 1);
  EXPECT_EQ(pooled.num_matched, 1);
  EXPECT_EQ(pooled.endpoint_t.size(), 2u);
}

TEST(SegmentEvaluationTest, Quantiles) {
  EXPECT_EQ(Quantile({}, 0.5), 0);
  EXPECT_DOUBLE_EQ(Quantile({3, 1, 2}, 0.5), 2);
  EXPECT_DOUBLE_EQ(Quantile({1, 2, 3, 4}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(Quantile({1, 2, 3, 4}, 1.0), 4);
}

TEST(SegmentEvaluationTest, ReadsVggLinesAndNamesTheBadLine) {
  const std::string dir = testing::MakeScratchDir("segment_evaluation");
  const std::string good = dir + "/good.lines", bad = dir + "/bad.lines";
  std::ofstream(good) << "86.1366 7.85548\t146.05 63.9401\n307.971 115.261\t279.961 113.549\n";
  std::ofstream(bad) << "1 2\t3 4\n5 6\t7\n";
  LineSegments segments;
  ASSERT_TRUE(ReadVggLines(good, &segments).ok());
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_DOUBLE_EQ(segments[1].p1.y(), 113.549);
  const Status status = ReadVggLines(bad, &segments);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("bad.lines:2"), std::string::npos) << status.message();
  EXPECT_FALSE(ReadVggLines(dir + "/missing.lines", &segments).ok());
}

}  // namespace
}  // namespace sfm
