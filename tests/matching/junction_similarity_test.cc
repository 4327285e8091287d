// Section 4.1 and 4.3: rho1, M(k) and its shift, the physical constraints (36)-(37).
#include "frontend/matching/junction_similarity.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "frontend/matching/matching_rule.h"
#include "frontend/matching/physical_constraints.h"
#include "tests/matching/synthetic_views.h"

namespace sfm {
namespace {

using testing::Junction3d;
using testing::ProjectedJunction;
using testing::TwoViews;

Eigen::Vector2d Direction(double degrees) {
  return Eigen::Vector2d(std::cos(degrees * M_PI / 180), std::sin(degrees * M_PI / 180));
}

TEST(JunctionSimilarityTest, Rho1) {
  const double R = 6;
  // (31): exp(-w R) = 0.01, so d = d' = R gives 0.01, d = d' = 0 gives 1, d = R/2 gives 0.1.
  EXPECT_NEAR(Rho1(R, R, R, Rho1Kind::kExponential), 0.01, 1e-15);
  EXPECT_NEAR(Rho1(0, 0, R, Rho1Kind::kExponential), 1, 1e-15);
  EXPECT_NEAR(Rho1(R / 2, R / 2, R, Rho1Kind::kExponential), 0.1, 1e-15);
  EXPECT_NEAR(Rho1(0, R, R, Rho1Kind::kExponential), 0.505, 1e-15);
  // Footnote 10: 0.5 (2 - (d + d')/R).
  EXPECT_NEAR(Rho1(R, R, R, Rho1Kind::kLinear), 0, 1e-15);
  EXPECT_NEAR(Rho1(0, R, R, Rho1Kind::kLinear), 0.5, 1e-15);
  EXPECT_NEAR(Rho1(1.5, 3, R, Rho1Kind::kLinear), 0.625, 1e-15);
}

TEST(JunctionSimilarityTest, SmallRotationRejectsAFlippedJunction) {
  // An L of 60 degrees and the same L turned by 180 degrees: (37) fails under both shifts.
  const Eigen::Vector2d l[] = {Direction(10), Direction(70)};
  const Eigen::Vector2d flipped[] = {-l[0], -l[1]};
  for (int shift = 0; shift < 2; ++shift) EXPECT_FALSE(IsSmallRotation(l, flipped, 2, shift)) << shift;
  // Turned by 8 degrees: both shifts keep every segment within 90 degrees of its partner; (36)
  // rejects the swapped one (its single turn changes sign).
  const Eigen::Vector2d turned[] = {Direction(18), Direction(78)};
  EXPECT_TRUE(IsSmallRotation(l, turned, 2, 0));
  EXPECT_TRUE(KeepsCyclicOrder(l, turned, 2, 0, 0.087));
  EXPECT_TRUE(IsSmallRotation(l, turned, 2, 1));
  EXPECT_FALSE(KeepsCyclicOrder(l, turned, 2, 1, 0.087));
}

// (36) and (37) together, as JunctionSimilarity::M applies them.
bool Allowed(const Eigen::Vector2d* n, const Eigen::Vector2d* n_prime, int num_segments, int shift) {
  return KeepsCyclicOrder(n, n_prime, num_segments, shift, 0.087) && IsSmallRotation(n, n_prime, num_segments, shift);
}

TEST(JunctionSimilarityTest, PhysicalConstraintsRejectMirroredJunctions) {
  // An ARROW (clockwise 0, 40, 120 degrees: turns 40, 80 and the reflex 240) and its mirror image
  // in the vertical axis, renumbered clockwise (60, 140, 180: turns 80, 40, 240). (36) keeps only
  // the shift that puts the reflex angle on the reflex angle, and (37) rejects that one.
  const Eigen::Vector2d arrow[] = {Direction(0), Direction(40), Direction(120)};
  const Eigen::Vector2d arrow_mirrored[] = {Direction(60), Direction(140), Direction(180)};
  EXPECT_TRUE(KeepsCyclicOrder(arrow, arrow_mirrored, 3, 0, 0.087));
  EXPECT_FALSE(IsSmallRotation(arrow, arrow_mirrored, 3, 0));
  for (int shift = 1; shift < 3; ++shift) EXPECT_FALSE(KeepsCyclicOrder(arrow, arrow_mirrored, 3, shift, 0.087));
  // The ARROW turned by 5 degrees and renumbered from another segment: exactly the right shift passes.
  const Eigen::Vector2d arrow_turned[] = {Direction(45), Direction(125), Direction(5)};
  EXPECT_TRUE(Allowed(arrow, arrow_turned, 3, 2));
  EXPECT_FALSE(Allowed(arrow, arrow_turned, 3, 0));
  EXPECT_FALSE(Allowed(arrow, arrow_turned, 3, 1));
  // An L mirrored (10, 70 -> 110, 170 degrees): one shift fails (36), the other (37).
  const Eigen::Vector2d l[] = {Direction(10), Direction(70)};
  const Eigen::Vector2d l_mirrored[] = {Direction(110), Direction(170)};
  EXPECT_FALSE(IsSmallRotation(l, l_mirrored, 2, 0));
  EXPECT_FALSE(KeepsCyclicOrder(l, l_mirrored, 2, 1, 0.087));
  // A Y has no reflex angle: it and its mirror image (0, 110, 230 -> 70, 180, 310 degrees) keep
  // the order under every shift, and here even (37) holds for one. Only the end-points (H) can
  // tell them apart; see MirroredOrFarOrDifferentJunctionsAreUnmatched.
  const Eigen::Vector2d y[] = {Direction(0), Direction(110), Direction(230)};
  const Eigen::Vector2d y_mirrored[] = {Direction(70), Direction(180), Direction(310)};
  for (int shift = 0; shift < 3; ++shift) EXPECT_TRUE(KeepsCyclicOrder(y, y_mirrored, 3, shift, 0.087));
  EXPECT_TRUE(Allowed(y, y_mirrored, 3, 0));
}

TEST(JunctionSimilarityTest, CyclicOrderSkipsTheBarOfAT) {
  // A T: bar halves at 0 and 180 degrees, stem at 90. The bar's turn is noise: +/- 0.1 degree.
  const Eigen::Vector2d t1[] = {Direction(0), Direction(90), Direction(180.1)};
  const Eigen::Vector2d t2[] = {Direction(1), Direction(91), Direction(180.9)};
  EXPECT_TRUE(KeepsCyclicOrder(t1, t2, 3, 0, std::sin(5 * M_PI / 180)));
  EXPECT_FALSE(KeepsCyclicOrder(t1, t2, 3, 0, 0));  // compared literally, the bar's sign flips
}

// One 3D Y junction seen by both cameras, with the segments of image 2 renumbered.
struct RotatedPair {
  Junctions a, b;
  int expected_shift;
};
RotatedPair MakeRotatedPair(int rotate_by) {
  const TwoViews views = testing::MakeTwoViews();
  std::mt19937 rng(5);
  const Junction3d junction3d = testing::RandomJunction3d(views, 3, &rng);
  const ProjectedJunction a = testing::ProjectJunction(views, 0, junction3d);
  ProjectedJunction b = testing::ProjectJunction(views, 1, junction3d);
  std::rotate(b.junction.segments.begin(), b.junction.segments.begin() + rotate_by, b.junction.segments.end());
  std::rotate(b.arm_of_segment.begin(), b.arm_of_segment.begin() + rotate_by, b.arm_of_segment.end());
  return {{a.junction}, {b.junction}, testing::TrueShift(a, b)};
}

TEST(JunctionSimilarityTest, MPicksTheShiftOfARenumberedJunction) {
  const TwoViews views = testing::MakeTwoViews();
  const MatchingOptions options;
  for (int rotate_by = 0; rotate_by < 3; ++rotate_by) {
    const RotatedPair pair = MakeRotatedPair(rotate_by);
    ASSERT_GE(pair.expected_shift, 0);
    const JunctionSimilarity similarity(pair.a, pair.b, views.F(), options);
    const PairSimilarity rho = similarity.Rho(0, 0);
    EXPECT_EQ(rho.shift, pair.expected_shift) << rotate_by;
    // Exact projections: d = d' = 0 and every H = -1/D, H H' = 1, so rho1 = rho2 = 1.
    EXPECT_NEAR(rho.rho, 1, 1e-9);
    const std::optional<double> best = similarity.M(0, 0, pair.expected_shift);
    ASSERT_TRUE(best.has_value());
    EXPECT_NEAR(*best, 1, 1e-9);
    for (int shift = 0; shift < 3; ++shift) {
      const std::optional<double> m = similarity.M(0, 0, shift);
      if (shift != pair.expected_shift && m) {
        EXPECT_LT(*m, *best);
      }
    }
  }
}

TEST(JunctionSimilarityTest, MirroredOrFarOrDifferentJunctionsAreUnmatched) {
  const TwoViews views = testing::MakeTwoViews();
  const MatchingOptions options;
  const RotatedPair pair = MakeRotatedPair(0);
  // Image 2's junction mirrored in the epipolar line of p0 (which runs through p'0).
  Junction mirrored = pair.b[0];
  const Eigen::Vector3d line = views.F() * pair.a[0].location.homogeneous();
  const Eigen::Vector2d normal = line.head<2>().normalized();
  for (JunctionSegment& segment : mirrored.segments) {
    const Eigen::Vector2d r = segment.end - mirrored.location;
    segment.end = mirrored.location + r - 2 * r.dot(normal) * normal;
  }
  std::reverse(mirrored.segments.begin(), mirrored.segments.end());  // clockwise again
  // Moved 11 px off the epipolar line (R = 10).
  Junction far = pair.b[0];
  far.location += 11 * normal;
  for (JunctionSegment& segment : far.segments) segment.end += 11 * normal;
  // An L: different segment count.
  Junction l = pair.b[0];
  l.segments.pop_back();
  const Junctions b = {pair.b[0], mirrored, far, l};
  const JunctionSimilarity similarity(pair.a, b, views.F(), options);
  EXPECT_TRUE(similarity.Rho(0, 0).Matched());
  for (int j = 1; j < 4; ++j) {
    const PairSimilarity rho = similarity.Rho(0, j);
    EXPECT_FALSE(rho.Matched()) << j;
    EXPECT_EQ(rho.rho, 0) << j;
  }
}

// Partial correspondence (docs/matching.md, "Partial correspondence"): exact images of one 3D Y
// junction, arm 2 missed in one image (an L). The best common subset pairs the L's two segments
// with the Y's segments of the same arms and leaves out the Y's arm-2 segment; with exact images
// every H H' is 1 (as for full pairs), so rho2 = 2/3 (the missing term counted as 0 over 3
// segments), rho1 = 1 (d = d' = 0) and rho = 0.5 (1 + 2/3) = 0.8333, below the full Y-Y rho of 1.
// Tolerance 1e-9 (rounding). Both ways round (L in image 1 or in image 2).
TEST(JunctionSimilarityTest, PartialRhoPairsAnLWithTheRightTwoSegmentsOfAY) {
  std::mt19937 rng(21);
  const TwoViews views = testing::MakeTwoViews();
  int trials_run = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Junction3d y3d = testing::RandomJunction3d(views, 3, &rng);
    const ProjectedJunction y_a = testing::ProjectJunction(views, 0, y3d);
    const ProjectedJunction y_b = testing::ProjectJunction(views, 1, y3d);
    const int dropped_arm = trial % 3;
    // A Y with two arms opposite within 5 degrees in an image reads as a T there (its bar); the
    // partial rules for those are tested in partial_correspondence_test.cc (trial 9: 184.3 deg).
    if (testing::HasLineThrough(y_a.junction, 5) || testing::HasLineThrough(y_b.junction, 5)) continue;
    ++trials_run;
    auto without_arm = [&](const ProjectedJunction& y, std::vector<int>* arms) {
      Junction l = y.junction;
      arms->clear();
      l.segments.clear();
      for (int s = 0; s < 3; ++s) {
        if (y.arm_of_segment[s] == dropped_arm) continue;
        l.segments.push_back(y.junction.segments[s]);
        arms->push_back(y.arm_of_segment[s]);
      }
      return l;
    };
    auto segment_of_arm = [](const ProjectedJunction& y, int arm) {
      return static_cast<int>(std::find(y.arm_of_segment.begin(), y.arm_of_segment.end(), arm) -
                              y.arm_of_segment.begin());
    };
    std::vector<int> arms_of_l;
    for (int l_in_a = 0; l_in_a < 2; ++l_in_a) {
      const Junction l = without_arm(l_in_a ? y_a : y_b, &arms_of_l);
      const Junctions a = {l_in_a ? l : y_a.junction};
      const Junctions b = {l_in_a ? y_b.junction : l};
      const JunctionSimilarity similarity(a, b, views.F(), MatchingOptions());
      EXPECT_FALSE(similarity.Rho(0, 0).Matched()) << "different counts: no full pair";
      const PairSimilarity partial = similarity.PartialRho(0, 0);
      ASSERT_TRUE(partial.Matched()) << trial;
      EXPECT_NEAR(partial.rho, 0.5 * (1 + 2.0 / 3), 1e-9) << trial;
      JunctionMatch match{0, 0, partial.rho, partial.shift, partial.missing_a, partial.missing_b};
      if (l_in_a) {
        EXPECT_EQ(partial.missing_a, -1);
        EXPECT_EQ(partial.missing_b, segment_of_arm(y_b, dropped_arm)) << trial;
        for (int i = 0; i < 2; ++i) {
          EXPECT_EQ(PartnerSegment(match, i, 2, 3), segment_of_arm(y_b, arms_of_l[i])) << trial;
        }
      } else {
        EXPECT_EQ(partial.missing_b, -1);
        EXPECT_EQ(partial.missing_a, segment_of_arm(y_a, dropped_arm)) << trial;
        for (int s = 0; s < 3; ++s) {
          const int arm = y_a.arm_of_segment[s];
          const int expected = arm == dropped_arm ? -1
                                                  : static_cast<int>(std::find(arms_of_l.begin(), arms_of_l.end(), arm) -
                                                                     arms_of_l.begin());
          EXPECT_EQ(PartnerSegment(match, s, 3, 2), expected) << trial;
        }
      }
    }
    // The full pair of the same vertex outranks the partial one.
    const JunctionSimilarity full({y_a.junction}, {y_b.junction}, views.F(), MatchingOptions());
    EXPECT_NEAR(full.Rho(0, 0).rho, 1, 1e-9);
    EXPECT_FALSE(full.PartialRho(0, 0).Matched()) << "equal counts are not partial";
  }
  EXPECT_GE(trials_run, 15);
}

// ToString / FromString (the --match_rho1 flag): every kind's name parses back to it; another name
// is an error naming the choices, and leaves the kind as it was.
// PossiblePartners' list: the junctions of b with the same segment count (or one apart with
// max_count_difference 1) and p'0 within R of the epipolar line of p0 (no pose: R =
// max_epipolar_distance_px), in increasing index. Figure protected: equal lists for 200 junctions
// of a against 800 of b, under a general F and under one whose epipolar lines are steep.
TEST(JunctionSimilarityTest, PossiblePartnersListsEveryJunctionWithinTheBand) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> x(-20, 660), y(-20, 500);
  std::uniform_int_distribution<int> segments(2, 4), edge(0, 20);
  auto random_junctions = [&](int n) {
    Junctions junctions(n);
    for (int i = 0; i < n; ++i) {
      junctions[i].id = i;
      junctions[i].location = {x(rng), y(rng)};
      if (i % 10 == 0) junctions[i].location.x() = 32.0 * edge(rng);
      if (i % 10 == 1) junctions[i].location.y() = 32.0 * edge(rng);
      for (int s = segments(rng); s > 0; --s) {
        junctions[i].segments.push_back({junctions[i].location + Direction(s * 100.0) * 30, -1});
      }
    }
    return junctions;
  };
  const Junctions a = random_junctions(200), b = random_junctions(800);
  Eigen::Matrix3d general, steep;
  general << 1e-6, -3e-4, 0.05, 3.1e-4, 2e-6, -0.2, -0.06, 0.19, 1;
  steep << 0, 0, 0.3, 0, 0, -0.001, -0.3, 0.002, 1;  // lines near x = const
  MatchingOptions options;
  options.max_epipolar_distance_px = 12;
  for (const Eigen::Matrix3d& F : {general, steep}) {
    const JunctionSimilarity similarity(a, b, F, options);
    for (int difference : {0, 1}) {
      for (int i = 0; i < static_cast<int>(a.size()); ++i) {
        Eigen::Vector3d line = F * a[i].location.homogeneous();
        line /= line.head<2>().norm();
        std::vector<int> expected;
        for (int j = 0; j < static_cast<int>(b.size()); ++j) {
          const double distance = std::abs(line(0) * b[j].location.x() + line(1) * b[j].location.y() + line(2));
          if (distance <= options.max_epipolar_distance_px &&
              std::abs(b[j].NumSegments() - a[i].NumSegments()) <= difference) {
            expected.push_back(j);
          }
        }
        std::vector<int> listed;
        similarity.PossiblePartners(i, &listed, difference);
        EXPECT_EQ(listed, expected) << "junction " << i << ", count difference " << difference;
      }
    }
  }
}

TEST(Rho1KindTest, NamesParseBackAndOthersAreRefused) {
  for (const Rho1Kind kind : {Rho1Kind::kExponential, Rho1Kind::kLinear}) {
    Rho1Kind parsed = kind == Rho1Kind::kLinear ? Rho1Kind::kExponential : Rho1Kind::kLinear;
    ASSERT_TRUE(FromString(ToString(kind), &parsed).ok()) << ToString(kind);
    EXPECT_EQ(parsed, kind);
  }
  Rho1Kind parsed = Rho1Kind::kLinear;
  const Status status = FromString("gaussian", &parsed);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("'exponential' or 'linear'"), std::string::npos) << status.message();
  EXPECT_EQ(parsed, Rho1Kind::kLinear);
}

}  // namespace
}  // namespace sfm
