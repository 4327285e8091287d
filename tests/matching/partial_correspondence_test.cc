// Which segment a partial junction correspondence may leave out (JunctionSimilarity::PartialRho,
// docs/matching.md "Partial correspondence", rules (a) and (b)): only one that detection can miss
// alone. Exact images of 3D T junctions (a straight bar through the location and a stem) in the
// two-view rig of the matching tests.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <random>

#include "frontend/matching/junction_similarity.h"
#include "frontend/matching/matching_rule.h"
#include "tests/matching/synthetic_views.h"

namespace sfm {
namespace {

using testing::Junction3d;
using testing::ProjectedJunction;
using testing::TwoViews;

// A 3D T: the random junction's arm 0 continued through the location as arm 2 (0.8 of its length),
// arm 1 the stem. Images well shaped in both views (20 px, 25 degrees), as RandomJunction3d's.
Junction3d RandomT(const TwoViews& views, std::mt19937* rng) {
  while (true) {
    Junction3d t = testing::RandomJunction3d(views, 2, rng);
    t.ends.push_back(t.location - 0.8 * (t.ends[0] - t.location));
    if (testing::IsWellShaped(testing::ProjectJunction(views, 0, t).junction, views, 20, 25) &&
        testing::IsWellShaped(testing::ProjectJunction(views, 1, t).junction, views, 20, 25)) {
      return t;
    }
  }
}

// The image junction with the segments of `arms` only (in its clockwise order); the bar's two
// halves (arms 0 and 2) come from one detected line segment when `bar_one_segment`, as junction
// detection gives them (JunctionSegment::line_segment), else from two.
Junction Keep(const ProjectedJunction& image, const std::vector<int>& arms, bool bar_one_segment) {
  Junction junction = image.junction;
  junction.segments.clear();
  for (size_t s = 0; s < image.junction.segments.size(); ++s) {
    const int arm = image.arm_of_segment[s];
    if (std::find(arms.begin(), arms.end(), arm) == arms.end()) continue;
    JunctionSegment segment = image.junction.segments[s];
    segment.line_segment = bar_one_segment && arm == 2 ? 0 : arm;
    junction.segments.push_back(segment);
  }
  return junction;
}

// Half of a bar may be the missed segment (docs/matching.md, "Partial correspondence"): an L made
// of half a T's bar and its stem matches the T, the T's missed segment being the bar half the L
// lacks, and the L's two segments paired with the T's of the same arms, in all 20 trials both ways
// round. This is what a true L vertex seen in the other frame as a T (another edge collinear with
// one arm) needs; occlusion T's are left to the guided pass's depth range test.
TEST(PartialCorrespondenceTest, ByDefaultHalfOfABarMayBeTheMissedSegment) {
  std::mt19937 rng(31);
  const TwoViews views = testing::MakeTwoViews();
  for (int trial = 0; trial < 20; ++trial) {
    const Junction3d t = RandomT(views, &rng);
    const ProjectedJunction t_a = testing::ProjectJunction(views, 0, t);
    const ProjectedJunction t_b = testing::ProjectJunction(views, 1, t);
    const bool bar_one_segment = trial % 2 == 0;
    for (int t_in_a = 0; t_in_a < 2; ++t_in_a) {
      const ProjectedJunction& whole_image = t_in_a ? t_a : t_b;
      const ProjectedJunction& l_image = t_in_a ? t_b : t_a;
      const Junction whole = Keep(whole_image, {0, 1, 2}, bar_one_segment);
      const Junction l = Keep(l_image, {0, 1}, bar_one_segment);  // bar half 2 missed
      const JunctionSimilarity similarity({t_in_a ? whole : l}, {t_in_a ? l : whole}, views.F(),
                                          MatchingOptions());
      const PairSimilarity rho = similarity.PartialRho(0, 0);
      ASSERT_TRUE(rho.Matched()) << trial << " " << t_in_a;
      // The exact images: rho = 0.5 (1 + 2/3).
      EXPECT_NEAR(rho.rho, 0.5 * (1 + 2.0 / 3), 1e-6) << trial << " " << t_in_a;
      JunctionMatch match{0, 0, rho.rho, rho.shift, rho.missing_a, rho.missing_b};
      const int missing = t_in_a ? match.missing_a : match.missing_b;
      ASSERT_GE(missing, 0);
      EXPECT_EQ(whole_image.arm_of_segment[missing], 2) << trial << " " << t_in_a;
      // The L's segments (arms 0 and 1, in its clockwise order) with the T's segments of the same arms.
      std::vector<int> l_arms;
      for (size_t s = 0; s < l_image.arm_of_segment.size(); ++s) {
        if (l_image.arm_of_segment[s] != 2) l_arms.push_back(l_image.arm_of_segment[s]);
      }
      if (t_in_a) {
        for (int s = 0; s < 3; ++s) {
          if (s == missing) continue;
          EXPECT_EQ(l_arms[PartnerSegment(match, s, 3, 2)], whole_image.arm_of_segment[s]) << trial;
        }
      } else {
        for (int i = 0; i < 2; ++i) {
          EXPECT_EQ(whole_image.arm_of_segment[PartnerSegment(match, i, 2, 3)], l_arms[i]) << trial;
        }
      }
    }
  }
}

// Rule (b): the bar alone, read in the other image as an L bent 10 degrees off the straight (a
// short half's end-point off by noise, as on VGG: an "L" of 164 degrees against a T's bar), is not
// a T whose stem was missed: without its stem the T is a straight line, the L has no line through
// its location. Image b's bar half 2 is turned 10 degrees about the location, beyond detection's
// 5-degree collinear tolerance. The stem is never the left-out segment, but a bar half may be: then the bent
// bar pairs with the T's stem and other bar half, the right location with a wrong segment correspondence (37
// tolerates up to 90 degrees between partner segments); this happens in 8 of the 20 trials, the price of the
// default stated in docs/matching.md ("Partial correspondence").
TEST(PartialCorrespondenceTest, ATWithoutItsStemIsALineNotAnL) {
  std::mt19937 rng(32);
  const TwoViews views = testing::MakeTwoViews();
  const double angle = 10 * 3.14159265358979323846 / 180;
  int matched = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Junction3d t = RandomT(views, &rng);
    const Junction whole = Keep(testing::ProjectJunction(views, 0, t), {0, 1, 2}, true);
    const ProjectedJunction t_b = testing::ProjectJunction(views, 1, t);
    Junction l = Keep(t_b, {0, 2}, false);
    for (size_t s = 0; s < l.segments.size(); ++s) {
      if (l.segments[s].line_segment != 2) continue;
      const Eigen::Vector2d v = l.segments[s].end - l.location;
      const double sign = trial % 2 == 0 ? 1 : -1;
      l.segments[s].end = l.location + Eigen::Rotation2Dd(sign * angle) * v;
    }
    ASSERT_FALSE(testing::HasLineThrough(l, 5)) << trial;
    const PairSimilarity rho =
        JunctionSimilarity({whole}, {l}, views.F(), MatchingOptions()).PartialRho(0, 0);
    if (!rho.Matched()) continue;
    ++matched;
    ASSERT_GE(rho.missing_a, 0);
    EXPECT_NE(testing::ProjectJunction(views, 0, t).arm_of_segment[rho.missing_a], 1)
        << trial << ": the stem left out";
  }
  EXPECT_EQ(matched, 8);
}

}  // namespace
}  // namespace sfm
