// Section 4.4: the rule (38), both ways, on hand-made candidate lists.
#include "frontend/matching/matching_rule.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

bool Contains(const std::vector<JunctionMatch>& matches, int a, int b) {
  for (const JunctionMatch& match : matches) {
    if (match.index_a == a && match.index_b == b) return true;
  }
  return false;
}

TEST(MatchingRuleTest, AmbiguousCandidatesWithinTau2AreNotMatched) {
  // Junction 0 has two near-identical candidates (0.80 and 0.75: 0.05 apart, tau2 = 0.1).
  const std::vector<JunctionMatch> candidates = {{0, 0, 0.80, 0}, {0, 1, 0.75, 0}, {1, 2, 0.6, 2}};
  const std::vector<JunctionMatch> matches = SelectMatches(candidates, 2, 3, 0.0, 0.1);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].index_a, 1);
  EXPECT_EQ(matches[0].index_b, 2);
  EXPECT_EQ(matches[0].shift, 2);
  EXPECT_EQ(matches[0].similarity, 0.6);
  // With tau2 = 0.04 the margin of 0.05 suffices.
  EXPECT_TRUE(Contains(SelectMatches(candidates, 2, 3, 0.0, 0.04), 0, 0));
}

TEST(MatchingRuleTest, BothDirectionsMustBeDistinct) {
  // Junction 3 of image 2 is the best partner of both 2 and 3 of image 1; 3 has no other candidate,
  // yet (38) from image 2's side picks 2 (0.9 against 0.5), so only (2, 3) is matched.
  const std::vector<JunctionMatch> candidates = {{2, 3, 0.9, 0}, {3, 3, 0.5, 0}};
  const std::vector<JunctionMatch> matches = SelectMatches(candidates, 4, 4, 0.0, 0.1);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_TRUE(Contains(matches, 2, 3));
  // 0.85 against 0.9: within tau2 from image 2's side, nobody matched.
  EXPECT_TRUE(SelectMatches({{2, 3, 0.9, 0}, {3, 3, 0.85, 0}}, 4, 4, 0.0, 0.1).empty());
}

TEST(MatchingRuleTest, Tau1RemovesCandidatesBeforeTheComparison) {
  // (5, 6) at 0.45 is not a candidate with tau1 = 0.46, so (5, 5) at 0.5 has no competitor.
  const std::vector<JunctionMatch> candidates = {{5, 5, 0.5, 0}, {5, 6, 0.45, 0}, {4, 4, 0.3, 0}};
  const std::vector<JunctionMatch> matches = SelectMatches(candidates, 6, 7, 0.46, 0.1);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_TRUE(Contains(matches, 5, 5));
  // tau1 = 0: (5, 6) competes and is within tau2; (4, 4) passes.
  const std::vector<JunctionMatch> all = SelectMatches(candidates, 6, 7, 0.0, 0.1);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_TRUE(Contains(all, 4, 4));
  // A tie is never distinct, even with tau2 = 0.
  EXPECT_TRUE(SelectMatches({{0, 0, 0.5, 0}, {0, 1, 0.5, 0}}, 1, 2, 0.0, 0.0).empty());
}

}  // namespace
}  // namespace sfm

namespace sfm {
namespace {

// SelectMatches' allied rivals (rivals on one arm, docs/matching.md): junctions 0 and 1 of
// image 1 both want junction 0 of image 2 (0.54 and 0.53). Without allies (38) refuses both (margin
// 0.01 <= tau2 = 0.1); allied, the larger is kept; a third, unallied rival at 0.50 still blocks it.
// Exact outcomes.
TEST(MatchingRuleTest, AlliedRivalsDoNotCountInTheMargin) {
  const std::vector<JunctionMatch> two = {{0, 0, 0.54}, {1, 0, 0.53}};
  const AlliedRivals allied = [](const JunctionMatch& x, const JunctionMatch& y) {
    return x.index_b == y.index_b && x.index_a + y.index_a == 1;
  };
  EXPECT_TRUE(SelectMatches(two, 3, 1, 0.0, 0.1).empty());
  const std::vector<JunctionMatch> kept = SelectMatches(two, 3, 1, 0.0, 0.1, allied);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].index_a, 0);
  std::vector<JunctionMatch> three = two;
  three.push_back({2, 0, 0.50});
  EXPECT_TRUE(SelectMatches(three, 3, 1, 0.0, 0.1, allied).empty());
}

}  // namespace
}  // namespace sfm
