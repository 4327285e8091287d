#include "frontend/junctions/pair_probability.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/test_segments.h"

namespace sfm {
namespace {

using testing::Segment;

TEST(EndpointModelTest, BothBranchesOfEquation5) {
  EndpointModel model;
  model.lambda = 1.0;
  model.mu = 0.2;
  EXPECT_DOUBLE_EQ(model.F(0), 1.0);
  EXPECT_NEAR(model.F(2.0), 0.1353352832366127, 1e-15);    // detected 2 px past the true end: e^-2
  EXPECT_NEAR(model.F(-5.0), 0.36787944117144233, 1e-15);  // detected 5 px short: e^(0.2*-5) = e^-1
}

TEST(PairProbabilityTest, SignOfTFollowsEquation8) {
  const SegmentLine s(Segment(0, 0, 10, 0));
  // p0 beyond p1: the segment stops 3 px short of it, t = (p1 - p0).n = -3.
  EndChange change = NearEndChange(s, Eigen::Vector2d(13, 0));
  EXPECT_EQ(change.near_end, 1);
  EXPECT_DOUBLE_EQ(change.t, -3);
  // p0 inside near p1: the segment runs 2 px past it, t = +2.
  change = NearEndChange(s, Eigen::Vector2d(8, 0));
  EXPECT_EQ(change.near_end, 1);
  EXPECT_DOUBLE_EQ(change.t, 2);
  // p0 before p0: outward is -n, t = (p0_detected - p0).(-n) = ((0,0) - (-4,0)).(-1,0) = -4.
  change = NearEndChange(s, Eigen::Vector2d(-4, 0));
  EXPECT_EQ(change.near_end, 0);
  EXPECT_DOUBLE_EQ(change.t, -4);
}

TEST(PairProbabilityTest, HandComputedPairs) {
  EndpointModel model;
  model.lambda = 1.0;
  model.mu = 0.2;
  const Eigen::Vector2d p0(13, 0);
  // a stops 3 px short (t = -3), b (upwards towards p0) stops 2 px short (t = -2):
  // f = e^(0.2*-3) * e^(0.2*-2) = e^-1.
  const SegmentLine b(Segment(13, 20, 13, 2));
  EXPECT_NEAR(PairProbability(SegmentLine(Segment(0, 0, 10, 0)), b, p0, model), std::exp(-1.0), 1e-15);
  // a' runs 1 px past p0 (t = +1): f = e^-1 * e^-0.4 = e^-1.4.
  EXPECT_NEAR(PairProbability(SegmentLine(Segment(0, 0, 14, 0)), b, p0, model), std::exp(-1.4), 1e-15);
}

// Hand-built cases with round numbers, independent of the fitted defaults.
JunctionDetectorOptions Options() {
  JunctionDetectorOptions options;
  options.endpoint_model.lambda = 1.0;
  options.endpoint_model.mu = 0.2;
  options.min_probability = 0.1;
  return options;
}

TEST(TestPairTest, EndToEndIsAnLContact) {
  const std::vector<SegmentLine> lines = {SegmentLine(Segment(0, 0, 10, 0)),
                                          SegmentLine(Segment(13, 20, 13, 2))};
  const auto hit = TestPair(lines, 0, 1, Options());
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->contact_a, Contact::kEnd1);
  EXPECT_EQ(hit->contact_b, Contact::kEnd1);
  EXPECT_NEAR(hit->probability, std::exp(-1.0), 1e-12);
  ASSERT_TRUE(hit->location.has_value());
  EXPECT_NEAR((*hit->location - Eigen::Vector2d(13, 0)).norm(), 0, 1e-12);
}

TEST(TestPairTest, EndOnInteriorIsATContactNotAnL) {
  // Stem end 4 px below the bar's interior: only the stem moves, f = e^(0.2*-4).
  const std::vector<SegmentLine> lines = {SegmentLine(Segment(0, 50, 100, 50)),
                                          SegmentLine(Segment(50, 100, 50, 54))};
  const auto hit = TestPair(lines, 0, 1, Options());
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->contact_a, Contact::kThrough);
  EXPECT_EQ(hit->contact_b, Contact::kEnd1);
  EXPECT_NEAR(hit->probability, std::exp(-0.8), 1e-12);
}

TEST(TestPairTest, ThresholdAndMaxGap) {
  JunctionDetectorOptions options = Options();
  // Gaps 6 and 6: e^(-2.4) = 0.091 < 0.1.
  const std::vector<SegmentLine> far = {SegmentLine(Segment(0, 0, 10, 0)),
                                        SegmentLine(Segment(16, 30, 16, 6))};
  EXPECT_FALSE(TestPair(far, 0, 1, options).has_value());
  options.min_probability = 0.09;
  EXPECT_TRUE(TestPair(far, 0, 1, options).has_value());
  options.max_gap_px = 5.5;
  EXPECT_FALSE(TestPair(far, 0, 1, options).has_value());
}

TEST(TestPairTest, CollinearPiecesOfOneLine) {
  // Gap of 6 px between facing ends, 0.5 px sideways: f = e^(0.2*-6).
  const std::vector<SegmentLine> lines = {SegmentLine(Segment(0, 0, 47, 0)),
                                          SegmentLine(Segment(100, 0.5, 53, 0.5)),
                                          SegmentLine(Segment(53, 3, 100, 3))};
  const auto hit = TestPair(lines, 0, 1, Options());
  ASSERT_TRUE(hit.has_value());
  EXPECT_FALSE(hit->location.has_value());
  EXPECT_EQ(hit->contact_a, Contact::kEnd1);
  EXPECT_EQ(hit->contact_b, Contact::kEnd1);
  EXPECT_NEAR(hit->probability, std::exp(-1.2), 1e-12);
  // 3 px sideways is another line.
  EXPECT_FALSE(TestPair(lines, 0, 2, Options()).has_value());
  // Side by side (overlapping, same way) is no continuation either.
  const std::vector<SegmentLine> side = {SegmentLine(Segment(0, 0, 47, 0)),
                                         SegmentLine(Segment(10, 1, 60, 1))};
  EXPECT_FALSE(TestPair(side, 0, 1, Options()).has_value());
}

}  // namespace
}  // namespace sfm
