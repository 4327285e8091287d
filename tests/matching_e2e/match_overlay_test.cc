// The Fig. 6-style match picture (pipeline/overlay/match_overlay.h): partner segments share a
// colour, also for a partial match (an L against a Y), whose left-out segment is drawn in grey.
#include "pipeline/overlay/match_overlay.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

Junction MakeJunction(const Eigen::Vector2d& location, const std::vector<Eigen::Vector2d>& ends) {
  Junction junction;
  junction.location = location;
  for (size_t i = 0; i < ends.size(); ++i) junction.segments.push_back({ends[i], static_cast<int>(i)});
  return junction;
}

// The colour at the middle of segment `s` of `junction`, drawn at scale 1, `offset_x` to the right.
cv::Vec3b MiddleColour(const cv::Mat& canvas, const Junction& junction, int s, int offset_x) {
  const Eigen::Vector2d middle = 0.5 * (junction.location + junction.segments[s].end);
  return canvas.at<cv::Vec3b>(static_cast<int>(std::lround(middle.y())),
                              static_cast<int>(std::lround(middle.x())) + offset_x);
}

bool IsGrey(const cv::Vec3b& c) { return c[0] == c[1] && c[1] == c[2]; }

TEST(MatchOverlayTest, APartialMatchColoursEachSegmentPairAlikeAndTheMissingSegmentGrey) {
  // Image 1: an L with arms right (0) and down (1); image 2: a Y with arms right (0), up (1) and
  // down (2). The partial match leaves the Y's up arm out (missing_b = 1): the L's right arm pairs
  // with the Y's right arm, its down arm with the Y's down arm (PartnerSegment).
  const cv::Mat image(100, 100, CV_8UC1, cv::Scalar(128));
  const Junctions a = {MakeJunction({50, 50}, {{90, 50}, {50, 90}})};
  const Junctions b = {MakeJunction({50, 50}, {{90, 50}, {50, 10}, {50, 90}})};
  JunctionMatch match{0, 0, 0.8, 0};
  match.missing_b = 1;
  ASSERT_EQ(PartnerSegment(match, 0, 2, 3), 0);
  ASSERT_EQ(PartnerSegment(match, 1, 2, 3), 2);
  const cv::Mat canvas = DrawMatchOverlay(image, a, image, b, {match}, 1);
  ASSERT_EQ(canvas.type(), CV_8UC3);
  const int offset_b = canvas.cols - image.cols;
  for (const auto& [segment_a, segment_b] : {std::pair{0, 0}, std::pair{1, 2}}) {
    const cv::Vec3b colour_a = MiddleColour(canvas, a[0], segment_a, 0);
    EXPECT_FALSE(IsGrey(colour_a)) << segment_a;
    EXPECT_EQ(colour_a, MiddleColour(canvas, b[0], segment_b, offset_b)) << segment_a << " " << segment_b;
  }
  EXPECT_NE(MiddleColour(canvas, a[0], 0, 0), MiddleColour(canvas, a[0], 1, 0));
  // The Y's up arm: grey (drawn like an unmatched junction's segments), not a palette colour.
  EXPECT_TRUE(IsGrey(MiddleColour(canvas, b[0], 1, offset_b)));
  EXPECT_NE(MiddleColour(canvas, b[0], 1, offset_b),
            cv::Vec3b(static_cast<uint8_t>(128 * 0.6 + 25), static_cast<uint8_t>(128 * 0.6 + 25),
                      static_cast<uint8_t>(128 * 0.6 + 25)));
}

}  // namespace
}  // namespace sfm
