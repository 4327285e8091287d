// Which segment a partial junction correspondence may leave out (JunctionSimilarity::PartialRho,
// docs/matching.md "Partial correspondence", rules (a) and (b)): only one that detection can miss
// alone. Exact images of 3D T junctions (a straight bar through the location and a stem) in the
// two-view rig of the matching tests.
#include <algorithm>
#include <random>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "frontend/matching/junction_similarity.h"
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

// Rule (a): an L made of half the bar and the stem (the other half of the bar not seen: what an
// occluding edge that the line passes behind gives) is not a T with a missed segment. The same L
// against a Y of the same three arms' directions bent off the straight would match (the existing
// Y-L test); here the pair must be unmatched in all 20 trials, both ways round, whether the bar is
// one detected segment or two collinear ones (opposite within 5 degrees).
TEST(PartialCorrespondenceTest, HalfOfABarIsNeverTheMissedSegment) {
  std::mt19937 rng(31);
  const TwoViews views = testing::MakeTwoViews();
  for (int trial = 0; trial < 20; ++trial) {
    const Junction3d t = RandomT(views, &rng);
    const ProjectedJunction t_a = testing::ProjectJunction(views, 0, t);
    const ProjectedJunction t_b = testing::ProjectJunction(views, 1, t);
    const bool bar_one_segment = trial % 2 == 0;
    for (int t_in_a = 0; t_in_a < 2; ++t_in_a) {
      const Junction whole = Keep(t_in_a ? t_a : t_b, {0, 1, 2}, bar_one_segment);
      const Junction l = Keep(t_in_a ? t_b : t_a, {0, 1}, bar_one_segment);  // bar half 2 missed
      const Junctions a = {t_in_a ? whole : l};
      const Junctions b = {t_in_a ? l : whole};
      const JunctionSimilarity similarity(a, b, views.F(), MatchingOptions());
      EXPECT_FALSE(similarity.PartialRho(0, 0).Matched()) << trial << " " << t_in_a;
    }
    // The full T against itself still matches (rules (a) and (b) concern partial pairs only).
    const JunctionSimilarity full({Keep(t_a, {0, 1, 2}, bar_one_segment)}, {Keep(t_b, {0, 1, 2}, bar_one_segment)},
                                  views.F(), MatchingOptions());
    EXPECT_TRUE(full.Rho(0, 0).Matched()) << trial;
  }
}

// Rule (b): the bar alone, read in the other image as an L bent 10 degrees off the straight (a
// short half's end-point off by noise, as on VGG: an "L" of 164 degrees against a T's bar), is not
// a T whose stem was missed: without its stem the T is a straight line, the L has no line through
// its location. Image b's bar half 2 is turned 10 degrees about the location, beyond detection's
// 5-degree collinear tolerance; unmatched in all 20 trials.
TEST(PartialCorrespondenceTest, ATWithoutItsStemIsALineNotAnL) {
  std::mt19937 rng(32);
  const TwoViews views = testing::MakeTwoViews();
  const double angle = 10 * 3.14159265358979323846 / 180;
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
    const JunctionSimilarity similarity({whole}, {l}, views.F(), MatchingOptions());
    EXPECT_FALSE(similarity.PartialRho(0, 0).Matched()) << trial;
  }
}

}  // namespace
}  // namespace sfm
