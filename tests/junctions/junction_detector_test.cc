#include "frontend/junctions/junction_detector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "tests/test_segments.h"

namespace sfm {
namespace {

using testing::Segment;

// A segment pointing away from `center` at image angle angle_deg (y down), stopping `gap` px short
// of it and `gap + 40` px long; the far end-point first.
LineSegment Spoke(const Eigen::Vector2d& center, double angle_deg, double gap) {
  const Eigen::Vector2d d(std::cos(angle_deg * M_PI / 180), std::sin(angle_deg * M_PI / 180));
  LineSegment s;
  s.p0 = center + (gap + 40) * d;
  s.p1 = center + gap * d;
  return s;
}

// Hand-built cases with round numbers, independent of the fitted defaults.
JunctionDetectorOptions Options() {
  JunctionDetectorOptions options;
  options.endpoint_model.lambda = 1.0;
  options.endpoint_model.mu = 0.2;
  options.min_probability = 0.1;
  return options;
}

Junctions DetectSpokes(std::initializer_list<double> angles, double gap) {
  const Eigen::Vector2d center(200, 150);
  LineSegments segments;
  for (double a : angles) segments.push_back(Spoke(center, a, gap));
  return DetectJunctions(segments, Options());
}

// The default threshold's rule (junction_options.h): with end-point offsets t drawn from the default
// model (density proportional to f), 90 % of pairs have a probability f(t1) f(t2) at or above it.
TEST(JunctionDetectorTest, DefaultThresholdKeepsNinetyPercentOfModelPairs) {
  const JunctionDetectorOptions options;
  const EndpointModel& model = options.endpoint_model;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::exponential_distribution<double> too_long(model.lambda), too_short(model.mu);
  auto draw = [&] {  // P(t >= 0) = mu / (lambda + mu) for the normalised two-sided density
    return uniform(rng) < model.mu / (model.lambda + model.mu) ? too_long(rng) : -too_short(rng);
  };
  const int n = 200000;
  int kept = 0;
  for (int i = 0; i < n; ++i) kept += model.F(draw()) * model.F(draw()) >= options.min_probability;
  EXPECT_NEAR(static_cast<double>(kept) / n, 0.90, 0.005);
}

TEST(JunctionDetectorTest, OptionsCheck) {
  EXPECT_TRUE(JunctionDetectorOptions().Check().ok());
  JunctionDetectorOptions options;
  options.min_probability = 0;
  EXPECT_EQ(options.Check().message(), "JunctionDetectorOptions: min_probability must be in (0, 1]");
  options = JunctionDetectorOptions();
  options.endpoint_model.mu = -1;
  EXPECT_FALSE(options.Check().ok());
  options = JunctionDetectorOptions();
  options.collinear_tolerance_deg = 0;
  EXPECT_FALSE(options.Check().ok());
  options = JunctionDetectorOptions();
  options.max_gap_px = NAN;
  EXPECT_FALSE(options.Check().ok());
}

TEST(JunctionDetectorTest, L) {
  // a stops 3 px short of (13, 0), b 2 px: probability e^(0.2*-3) e^(0.2*-2) = e^-1.
  const Junctions junctions = DetectJunctions({Segment(0, 0, 10, 0), Segment(13, 20, 13, 2)}, Options());
  ASSERT_EQ(junctions.size(), 1u);
  const Junction& j = junctions[0];
  EXPECT_EQ(j.id, 0);
  EXPECT_EQ(j.type, JunctionType::kL);
  EXPECT_NEAR((j.location - Eigen::Vector2d(13, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(j.score, std::exp(-1.0), 1e-12);
  // Clockwise on screen from the arm pointing down (b's far end) to the one pointing left (a's).
  ASSERT_EQ(j.NumSegments(), 2);
  EXPECT_EQ(j.segments[0].line_segment, 1);
  EXPECT_EQ(j.segments[0].end, Eigen::Vector2d(13, 20));
  EXPECT_EQ(j.segments[1].line_segment, 0);
  EXPECT_EQ(j.segments[1].end, Eigen::Vector2d(0, 0));
}

TEST(JunctionDetectorTest, Y) {
  const Junctions junctions = DetectSpokes({270, 30, 150}, 3);
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].type, JunctionType::kY);
  EXPECT_NEAR((junctions[0].location - Eigen::Vector2d(200, 150)).norm(), 0, 1e-9);
  EXPECT_NEAR(junctions[0].score, 3 * std::exp(-1.2), 1e-12);  // three pairs, each e^(0.2*-3)^2
}

TEST(JunctionDetectorTest, Arrow) {
  const Junctions junctions = DetectSpokes({0, 60, 120}, 3);
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].type, JunctionType::kArrow);
  EXPECT_EQ(junctions[0].NumSegments(), 3);
}

TEST(JunctionDetectorTest, TSplitsTheBarAndReportsNoL) {
  // Bar along y = 50, stem from below stopping 3 px short of it.
  const Junctions junctions = DetectJunctions({Segment(0, 50, 100, 50), Segment(50, 100, 50, 53)}, Options());
  ASSERT_EQ(junctions.size(), 1u);
  const Junction& j = junctions[0];
  EXPECT_EQ(j.type, JunctionType::kT);
  EXPECT_NEAR((j.location - Eigen::Vector2d(50, 50)).norm(), 0, 1e-12);
  EXPECT_NEAR(j.score, std::exp(-0.6), 1e-12);  // only the stem moves
  // Clockwise: the bar's right half, the stem (down), the bar's left half.
  ASSERT_EQ(j.NumSegments(), 3);
  EXPECT_EQ(j.segments[0].end, Eigen::Vector2d(100, 50));
  EXPECT_EQ(j.segments[0].line_segment, 0);
  EXPECT_EQ(j.segments[1].end, Eigen::Vector2d(50, 100));
  EXPECT_EQ(j.segments[1].line_segment, 1);
  EXPECT_EQ(j.segments[2].end, Eigen::Vector2d(0, 50));
  EXPECT_EQ(j.segments[2].line_segment, 0);
}

TEST(JunctionDetectorTest, TWithABarBrokenAtTheJunction) {
  const Junctions junctions = DetectJunctions(
      {Segment(0, 50, 47, 50), Segment(100, 50, 53, 50), Segment(50, 100, 50, 53)}, Options());
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].type, JunctionType::kT);
  EXPECT_NEAR((junctions[0].location - Eigen::Vector2d(50, 50)).norm(), 0, 1e-12);
  // Two stem-piece pairs and the pieces' own continuation (gap 6), each e^-1.2.
  EXPECT_NEAR(junctions[0].score, 3 * std::exp(-1.2), 1e-12);
}

TEST(JunctionDetectorTest, TNearTheBarsEndIsAnL) {
  // The stem meets the bar 1 px inside its end (less than min_arm_px): the bar's end moves.
  const Junctions junctions = DetectJunctions({Segment(0, 50, 51, 50), Segment(50, 100, 50, 53)}, Options());
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].type, JunctionType::kL);
  EXPECT_NEAR(junctions[0].score, std::exp(-1.0 - 0.6), 1e-12);
}

// Four ends meeting at one point are one X. The end-likelihood choice scores the X and the two L's of the
// same end-points alike (each end-point once, same location): the tie must go to the one junction (the
// weight's floor is not added per junction, and a sum equal within rounding is a tie).
TEST(JunctionDetectorTest, XFromFourEnds) {
  const Junctions junctions = DetectSpokes({0, 90, 180, 270}, 3);
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].type, JunctionType::kX);
  EXPECT_EQ(junctions[0].NumSegments(), 4);
  EXPECT_NEAR((junctions[0].location - Eigen::Vector2d(200, 150)).norm(), 0, 1e-9);
}

// Four ends meeting at a vertex whose two lines are not exactly concurrent (the left spoke 0.6 px
// lower): each L of two of them sits at its own intersection, so under the end-likelihood choice
// two L's explain the four ends better than the X at their mean; but their union is a candidate
// (every pair between them passes within max_gap), one junction by the paper's N-junction rule:
// the output is the X (MergeCoincidingJunctions), not two L's 0.6 px apart.
TEST(JunctionDetectorTest, NearlyConcurrentFourEndsAreOneX) {
  const Eigen::Vector2d center(200, 150);
  LineSegments segments = {Spoke(center, 0, 3), Spoke(center + Eigen::Vector2d(0, 0.6), 180, 3),
                           Spoke(center, 90, 3), Spoke(center, 270, 3)};
  const Junctions junctions = DetectJunctions(segments, Options());
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].type, JunctionType::kX);
  EXPECT_EQ(junctions[0].NumSegments(), 4);
  EXPECT_LT((junctions[0].location - (center + Eigen::Vector2d(0, 0.3))).norm(), 0.31);
}

TEST(JunctionDetectorTest, XFromTwoCrossingSegments) {
  const Junctions junctions = DetectJunctions({Segment(0, 0, 100, 100), Segment(0, 100, 100, 0)}, Options());
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].type, JunctionType::kX);
  EXPECT_EQ(junctions[0].NumSegments(), 4);
  EXPECT_NEAR((junctions[0].location - Eigen::Vector2d(50, 50)).norm(), 0, 1e-12);
  EXPECT_DOUBLE_EQ(junctions[0].score, 1.0);
}

TEST(JunctionDetectorTest, N) {
  const Junctions junctions = DetectSpokes({0, 72, 144, 216, 288}, 3);
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_EQ(junctions[0].type, JunctionType::kN);
  EXPECT_EQ(junctions[0].NumSegments(), 5);
  EXPECT_NEAR(junctions[0].score, 10 * std::exp(-1.2), 1e-12);
}

TEST(JunctionDetectorTest, NoJunction) {
  EXPECT_TRUE(DetectJunctions({}, Options()).empty());
  // Ends 7 px short each: e^-2.8 < 0.1.
  EXPECT_TRUE(DetectJunctions({Segment(0, 0, 10, 0), Segment(17, 30, 17, 7)}, Options()).empty());
  // One line broken in two is not a junction.
  EXPECT_TRUE(DetectJunctions({Segment(0, 0, 47, 0), Segment(53, 0, 100, 0)}, Options()).empty());
  // Degenerate and non-finite segments are ignored.
  EXPECT_TRUE(
      DetectJunctions({Segment(5, 5, 5, 5), Segment(0, 0, NAN, 3), Segment(0, 0, 10, 0)}, Options()).empty());
}

TEST(JunctionDetectorTest, AnEndPointJoinsOneJunction) {
  // a's end (10, 0) could close an L with b at (12, 0) (e^-0.8) or with c at (9, 0) (e^-1.6);
  // b and c are parallel, 3 px apart: no 3-junction. The stronger L wins, c is left alone.
  const Junctions junctions =
      DetectJunctions({Segment(0, 0, 10, 0), Segment(12, -20, 12, -2), Segment(9, 20, 9, 3)}, Options());
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_NEAR((junctions[0].location - Eigen::Vector2d(12, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(junctions[0].score, std::exp(-0.8), 1e-12);
}

TEST(JunctionDetectorTest, ConflictingEndPointGoesToTheBestOverallReading) {
  // A thin face: b and c parallel, 3 px apart, a ending between them. a's end (10, 0) closes an L
  // with b at (12, 0) (both ends 2 px short: e^-0.8 = 0.449) or with c at (9, 0) (a 1 px past,
  // c 3 px short: e^-1.6 = 0.202); b's end (12, -2) also closes an L with d at (12, -2) (d 5 px
  // short: e^-1.0 = 0.368). c and d alone fail (e^-2.6 < 0.1). Taking the strongest pair first
  // (a-b) would leave one junction, score 0.449, and lose both vertices at (9, 0) and (12, -2);
  // the best conflict-free set is a-c + b-d, score 0.570, every end-point used once.
  const Junctions junctions = DetectJunctions(
      {Segment(0, 0, 10, 0), Segment(12, -20, 12, -2), Segment(9, 20, 9, 3), Segment(40, -2, 17, -2)},
      Options());
  ASSERT_EQ(junctions.size(), 2u);
  std::vector<std::pair<double, double>> found;
  for (const Junction& j : junctions) found.emplace_back(j.location.x(), j.location.y());
  std::sort(found.begin(), found.end());
  EXPECT_NEAR(found[0].first, 9, 1e-9);
  EXPECT_NEAR(found[0].second, 0, 1e-9);
  EXPECT_NEAR(found[1].first, 12, 1e-9);
  EXPECT_NEAR(found[1].second, -2, 1e-9);
  EXPECT_NEAR(junctions[0].score + junctions[1].score, std::exp(-1.6) + std::exp(-1.0), 1e-12);
}

// The end-likelihood choice (the fitted default model, lambda 0.844, mu 0.353, threshold 0.0205). c
// and d meet at the origin (both 1 px short, f = 0.703 each); a stops 5 px short of it (f = 0.171)
// and runs 0.5 px past a vertical b at (-5.5, 0), which stops 4 px short there (f = 0.244). The
// paper's score prefers the 3-junction a-c-d (0.494 + 2 x 0.120 = 0.734) to the L a-b plus c-d
// (0.160 + 0.494 = 0.654), since a's weak pairs count twice; the end-points' log-likelihood ratios
// (ln f + 1.943 each, positive part) prefer the L plus c-d (1.52 + 0.53 + 2 x 1.59 = 5.23) to a-c-d
// (0.18 + 2 x 1.59 = 3.36): two junctions, at (-5.5, 0) and at the origin, to 1e-9 px.
TEST(JunctionDetectorTest, EndLikelihoodChoiceCountsEachEndPointOnce) {
  const LineSegments segments = {Segment(-40, 0, -5, 0), Segment(-5.5, 44, -5.5, 4), Segment(0, -40, 0, -1),
                                 Segment(28.2843, 28.2843, 0.707107, 0.707107)};
  const Junctions by_likelihood = DetectJunctions(segments, JunctionDetectorOptions());
  ASSERT_EQ(by_likelihood.size(), 2u);
  std::vector<std::pair<double, double>> found;
  for (const Junction& j : by_likelihood) {
    EXPECT_EQ(j.segments.size(), 2u);
    found.emplace_back(j.location.x(), j.location.y());
  }
  std::sort(found.begin(), found.end());
  EXPECT_NEAR(found[0].first, -5.5, 1e-9);
  EXPECT_NEAR(found[0].second, 0, 1e-9);
  EXPECT_NEAR(found[1].first, 0, 1e-6);
  EXPECT_NEAR(found[1].second, 0, 1e-6);
}

TEST(JunctionDetectorTest, BarHoldsATAndEndsInAnL) {
  const Junctions junctions =
      DetectJunctions({Segment(0, 50, 100, 50), Segment(50, 100, 50, 53), Segment(0, 100, 0, 52)}, Options());
  ASSERT_EQ(junctions.size(), 2u);
  std::vector<JunctionType> types = {junctions[0].type, junctions[1].type};
  std::sort(types.begin(), types.end());
  EXPECT_EQ(types, (std::vector<JunctionType>{JunctionType::kL, JunctionType::kT}));
}

// Drawings of cubes seen from a corner: a hexagon outline with three inner edges meeting at its
// centre, giving a Y at the centre, an ARROW at every other outline vertex and an L between.
struct CubeScene {
  LineSegments segments;
  std::vector<Eigen::Vector2d> vertices;
  std::vector<JunctionType> types;
};

CubeScene MakeCubes(int columns, int rows, double end_noise_px, std::mt19937* rng) {
  std::uniform_real_distribution<double> gap(0.5, 4.0);
  std::normal_distribution<double> noise(0.0, end_noise_px);
  std::bernoulli_distribution flip(0.5);
  CubeScene scene;
  auto add = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d d = (b - a).normalized();
    LineSegment s;
    s.p0 = a + gap(*rng) * d + Eigen::Vector2d(noise(*rng), noise(*rng));
    s.p1 = b - gap(*rng) * d + Eigen::Vector2d(noise(*rng), noise(*rng));
    if (flip(*rng)) std::swap(s.p0, s.p1);
    scene.segments.push_back(s);
  };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const Eigen::Vector2d center(60 + 100 * c, 60 + 100 * r);
      Eigen::Vector2d hexagon[6];
      for (int k = 0; k < 6; ++k) {
        const double a = (-90 + 60 * k) * M_PI / 180;
        hexagon[k] = center + 40 * Eigen::Vector2d(std::cos(a), std::sin(a));
        scene.vertices.push_back(hexagon[k]);
        scene.types.push_back(k % 2 == 0 ? JunctionType::kArrow : JunctionType::kL);
      }
      scene.vertices.push_back(center);
      scene.types.push_back(JunctionType::kY);
      for (int k = 0; k < 6; ++k) add(hexagon[k], hexagon[(k + 1) % 6]);
      for (int k = 0; k < 6; k += 2) add(center, hexagon[k]);
    }
  }
  return scene;
}

// Speed is measured by build/bin/benchmark_junctions, not here (timed unit tests flake on shared machines).
TEST(JunctionDetectorTest, ThirtyCubesAllVertices) {
  std::mt19937 rng(7);
  const CubeScene scene = MakeCubes(6, 5, /*end_noise_px=*/0.1, &rng);
  ASSERT_EQ(scene.segments.size(), 270u);
  const Junctions junctions = DetectJunctions(scene.segments, Options());
  EXPECT_EQ(junctions.size(), scene.vertices.size());
  for (size_t v = 0; v < scene.vertices.size(); ++v) {
    const auto nearest =
        std::min_element(junctions.begin(), junctions.end(), [&](const Junction& a, const Junction& b) {
          return (a.location - scene.vertices[v]).norm() < (b.location - scene.vertices[v]).norm();
        });
    ASSERT_NE(nearest, junctions.end());
    EXPECT_LT((nearest->location - scene.vertices[v]).norm(), /*max_error_px=*/1.0) << v;
    EXPECT_EQ(nearest->type, scene.types[v]) << v;
  }
  for (size_t j = 0; j < junctions.size(); ++j) EXPECT_EQ(junctions[j].id, static_cast<int>(j));
}

// A corner beyond a taken end-point (the fitted default model: mu 0.353, threshold 0.0205, per-end-point
// baseline ln sqrt(0.0205) = -1.943). Two true vertices on one vertical line: W = (0, 0), where a
// (from above) ends 1 px short and x (the diagonal from the lower left) ends 1 px short, and
// V = (0, 4), 4 px further down a's line, where b (from the right) ends 1 px short. b's ray meets
// x's line at P = (-4, 4), 4.66 px inside x (a T, b 5 px short: f = 0.171). The choice takes the L
// a-x at W (a's end-point explained 1 px short, not 5) and, for b, the T at P: a's end-point belongs
// to one junction. With the rule, a's line also serves V (4 px beyond W, over min_arm_px = 3): b's
// end-point is explained there 1 px short (ln f + 1.943 = 1.59 against 0.18 at P), so the T becomes
// the L a-b at V. Protects: the two junctions at W and V to 1e-9 px, and the T at P when the stub
// W-V is under min_arm_px.
TEST(JunctionDetectorTest, CornerBeyondATakenEndReplacesTheT) {
  auto segments_with_gap = [](double gap) {
    // b 1 px short of V = (0, gap); x's line y = -x meets b's line at (-gap, gap).
    return LineSegments{Segment(0, -40, 0, -1), Segment(-30, 30, -0.707107, 0.707107),
                        Segment(40, gap, 1, gap)};
  };
  auto sorted_locations = [](const Junctions& junctions) {
    std::vector<std::pair<double, double>> found;
    for (const Junction& j : junctions) found.emplace_back(j.location.x(), j.location.y());
    std::sort(found.begin(), found.end());
    return found;
  };
  JunctionDetectorOptions options;
  const Junctions with_rule = DetectJunctions(segments_with_gap(4), options);
  const auto with = sorted_locations(with_rule);
  ASSERT_EQ(with.size(), 2u);
  EXPECT_NEAR(with[0].first, 0, 1e-9);  // W
  EXPECT_NEAR(with[0].second, 0, 1e-9);
  EXPECT_NEAR(with[1].first, 0, 1e-9);  // V
  EXPECT_NEAR(with[1].second, 4, 1e-9);
  for (const Junction& j : with_rule) EXPECT_EQ(j.type, JunctionType::kL);

  // With min_arm_px = 4.5 the stub W-V (4 px) is under it, not told from a's end overshooting W;
  // the T (4.66 px inside x, still a T) stays.
  options.min_arm_px = 4.5;
  const auto short_stub = sorted_locations(DetectJunctions(segments_with_gap(4), options));
  ASSERT_EQ(short_stub.size(), 2u);
  EXPECT_NEAR(short_stub[0].first, -4, 1e-6);
  EXPECT_NEAR(short_stub[0].second, 4, 1e-6);
}

// A corner beyond a taken end-point for a free end-point: as above, but x comes from the upper left (its line
// y = x meets b's line at (4, 4), inside b, where x would run 6.6 px past its end: no T), so b's end-point is
// in no junction by the choice, which finds only W = (0, 0). a's line also serves V = (0, 4), 4 px
// beyond W: b's end 1 px short there (ln f + 1.943 = 1.59 > 0), the corner a-b is added.
// Protects: W and V to 1e-9 px.
TEST(JunctionDetectorTest, CornerBeyondATakenEndServesAFreeEndPoint) {
  const LineSegments segments = {Segment(0, -40, 0, -1), Segment(-30, -30, -0.707107, -0.707107),
                                 Segment(40, 4, 1, 4)};
  const Junctions junctions = DetectJunctions(segments, JunctionDetectorOptions());
  ASSERT_EQ(junctions.size(), 2u);
  std::vector<std::pair<double, double>> found;
  for (const Junction& j : junctions) found.emplace_back(j.location.x(), j.location.y());
  std::sort(found.begin(), found.end());
  EXPECT_NEAR(found[0].first, 0, 1e-9);  // W
  EXPECT_NEAR(found[0].second, 0, 1e-9);
  EXPECT_NEAR(found[1].first, 0, 1e-9);  // V
  EXPECT_NEAR(found[1].second, 4, 1e-9);
}

// The same with an L of c (vertical, x = -2, from below) and d (horizontal, y = 6, from the left)
// at (-2, 6), 2.83 px from V = (0, 4): c and d are parallel to a and b (2 px off their lines: no
// intersection, no collinear link), and their pairs with a and b lose to W and to the L c-d. The
// corner at V is within min_arm_px of the L c-d, not told apart from it, so none is added.
// Protects: 2 junctions (W and the L c-d), not 3.
TEST(JunctionDetectorTest, CornerBeyondATakenEndNotNextToAnotherJunction) {
  const LineSegments segments = {Segment(0, -40, 0, -1), Segment(-30, -30, -0.707107, -0.707107),
                                 Segment(40, 4, 1, 4), Segment(-2, 46, -2, 7), Segment(-42, 6, -3, 6)};
  const Junctions junctions = DetectJunctions(segments, JunctionDetectorOptions());
  ASSERT_EQ(junctions.size(), 2u);
  std::vector<std::pair<double, double>> found;
  for (const Junction& j : junctions) found.emplace_back(j.location.x(), j.location.y());
  std::sort(found.begin(), found.end());
  EXPECT_NEAR(found[0].first, -2, 1e-9);  // the L c-d
  EXPECT_NEAR(found[0].second, 6, 1e-9);
  EXPECT_NEAR(found[1].first, 0, 1e-9);  // W
  EXPECT_NEAR(found[1].second, 0, 1e-9);
}

}  // namespace
}  // namespace sfm
