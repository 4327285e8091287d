#include "pipeline/report/plot.h"

#include <cmath>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace sfm::plot {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAre;

TEST(NiceTicksTest, HandCases) {
  EXPECT_THAT(NiceTicks(0, 7.3, 6), ElementsAre(0, 2, 4, 6));
  EXPECT_THAT(NiceTicks(0, 7.3, 8), ElementsAre(0, 1, 2, 3, 4, 5, 6, 7));
  EXPECT_THAT(NiceTicks(-1, 1, 5), ElementsAre(-1, -0.5, 0, 0.5, 1));
  EXPECT_THAT(NiceTicks(0, 0.034, 6),
              ElementsAre(0, DoubleNear(0.01, 1e-15), DoubleNear(0.02, 1e-15), DoubleNear(0.03, 1e-15)));
  EXPECT_THAT(NiceTicks(13, 87, 5), ElementsAre(20, 40, 60, 80));
  EXPECT_THAT(NiceTicks(-0.5, 39.5, 10), ElementsAre(0, 5, 10, 15, 20, 25, 30, 35));
  EXPECT_THAT(NiceTicks(1850, 1850.4, 5), ElementsAre(1850, DoubleNear(1850.1, 1e-9), DoubleNear(1850.2, 1e-9),
                                                      DoubleNear(1850.3, 1e-9), DoubleNear(1850.4, 1e-9)));
}

TEST(NiceTicksTest, MinimumStepKeepsWholeNumbers) {
  EXPECT_THAT(NiceTicks(-0.5, 2.5, 10, 1.0), ElementsAre(0, 1, 2));
  EXPECT_THAT(NiceTicks(-0.5, 2.5, 10), ElementsAre(-0.5, 0, 0.5, 1, 1.5, 2, 2.5));
}

TEST(NiceTicksTest, DegenerateRangesGiveNoTicks) {
  EXPECT_TRUE(NiceTicks(1, 1, 5).empty());
  EXPECT_TRUE(NiceTicks(2, 1, 5).empty());
  EXPECT_TRUE(NiceTicks(0, NAN, 5).empty());
  EXPECT_TRUE(NiceTicks(0, INFINITY, 5).empty());
}

// The largest 1, 2 or 5 x 10^k within a quarter of the range.
TEST(ScaleBarLengthTest, HandCases) {
  EXPECT_DOUBLE_EQ(ScaleBarLength(12.0), 2.0);
  EXPECT_DOUBLE_EQ(ScaleBarLength(20.0), 5.0);
  EXPECT_DOUBLE_EQ(ScaleBarLength(4.0), 1.0);
  EXPECT_DOUBLE_EQ(ScaleBarLength(0.9), 0.2);
  EXPECT_DOUBLE_EQ(ScaleBarLength(60.0), 10.0);
  EXPECT_EQ(ScaleBarLength(0.0), 0.0);
  EXPECT_EQ(ScaleBarLength(std::nan("")), 0.0);
}

TEST(TickLabelTest, DecimalsFollowTheStep) {
  EXPECT_EQ(TickLabel(4, 2), "4");
  EXPECT_EQ(TickLabel(0.5, 0.5), "0.5");
  EXPECT_EQ(TickLabel(0.30000000000000004, 0.1), "0.3");
  EXPECT_EQ(TickLabel(0.02, 0.01), "0.02");
  EXPECT_EQ(TickLabel(-1e-17, 0.1), "0.0");
  EXPECT_EQ(TickLabel(-2.5, 0.5), "-2.5");
  EXPECT_EQ(TickLabel(1500, 500), "1500");
}

TEST(PlotTest, RendersAtTheAskedSizeWithDataInside) {
  Plot figure(800, 400);
  figure.SetTitle("title");
  figure.SetXLabel("x [m]");
  figure.SetYLabel("y [m]");
  figure.AddLine({0, 1, 2, 3}, {0, 1, 0, NAN}, colour::kBlue, "line", 2);
  figure.AddBars({1, 2, 3}, colour::kOrange, "bars");
  figure.AddSegments({{0, 0, 3, 3}}, colour::kGreen, "segments");
  figure.AddMarkers({1.5}, {0.5}, colour::kVermillion, "dot", 4);
  const cv::Mat image = figure.Render();
  ASSERT_EQ(image.cols, 800);
  ASSERT_EQ(image.rows, 400);
  ASSERT_EQ(image.type(), CV_8UC3);
  // Each colour appears somewhere.
  for (const cv::Scalar& c : {colour::kBlue, colour::kOrange, colour::kGreen, colour::kVermillion}) {
    cv::Mat mask;
    cv::inRange(image, c, c, mask);
    EXPECT_GT(cv::countNonZero(mask), 10) << c;
  }
}

TEST(PlotTest, EmptyPlotStillDrawsAxes) {
  Plot figure(400, 300);
  const cv::Mat image = figure.Render();
  ASSERT_EQ(image.size(), cv::Size(400, 300));
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey < 128), 100);  // the frame and tick labels
}

}  // namespace
}  // namespace sfm::plot
