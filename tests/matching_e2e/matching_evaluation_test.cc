// The evaluation code of benchmark_matching (benchmarks/evaluation/matching_evaluation.h), on
// hand-built cases, and its reading of the VGG Corridor ground truth when the data is present.
#include "benchmarks/evaluation/matching_evaluation.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "geometry/epipolar.h"
#include "benchmarks/evaluation/segment_evaluation.h"
#include "tests/test_data.h"
#include "tests/test_segments.h"

namespace sfm {
namespace {

using testing::Segment;

// F of a camera translated along +x (K = identity-like, f = 500, principal point (320, 240)):
// epipolar lines are horizontal, x2^T F x1 = 0 means equal y.
Eigen::Matrix3d SidewaysF() {
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  return FundamentalFromPoses(K, Pose3(), Pose3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.5, 0, 0)));
}

TEST(MatchingEvaluationTest, NearestWithinTakesTheNearestTargetInsideTheRadius) {
  const std::vector<Eigen::Vector2d> targets = {{0, 0}, {2, 0}, {10, 10}};
  const std::vector<int> nearest = NearestWithin({{0.4, 0}, {1.4, 0}, {5, 5}, {10, 12.9}}, targets, 3.0);
  EXPECT_EQ(nearest, (std::vector<int>{0, 1, -1, 2}));
}

TEST(MatchingEvaluationTest, EpipolarConsistencyIsTestedBothWays) {
  const Eigen::Matrix3d F = SidewaysF();
  EXPECT_TRUE(EpipolarConsistent(F, {100, 200}, {60, 201.5}, 2.0));
  EXPECT_FALSE(EpipolarConsistent(F, {100, 200}, {60, 202.5}, 2.0));
}

TEST(MatchingEvaluationTest, JudgeMatchesSplitsEpipolarAndIdentityFailures) {
  const Eigen::Matrix3d F = SidewaysF();
  const std::vector<Eigen::Vector2d> a = {{100, 100}, {200, 200}, {300, 300}, {400, 400}};
  const std::vector<Eigen::Vector2d> b = {{90, 100}, {190, 210}, {290, 300}, {390, 400}};
  // Identity: match 0 the same, match 2 different, match 3 unknown.
  const SameFeature same = [](int ia, int ib) { return ia == 0 ? 1 : ia == 2 ? 0 : -1; };
  const MatchVerdicts v = JudgeMatches({{0, 0}, {1, 1}, {2, 2}, {3, 3}}, a, b, F, 2.0, same);
  EXPECT_EQ(v.matches, 4);
  EXPECT_EQ(v.correct, 2);         // 0 (same, on the line) and 3 (unknown, on the line)
  EXPECT_EQ(v.epipolar_wrong, 1);  // 1: 10 px off
  EXPECT_EQ(v.identity_wrong, 1);  // 2
  EXPECT_EQ(v.identity_known, 2);
  EXPECT_EQ(v.correct_known, 1);
  EXPECT_EQ(v.Wrong(), 2);
}

TEST(MatchingEvaluationTest, CountRecallNeedsTheFeatureSeenInBothAndJoined) {
  // Detections of image 1 lie on true features 5, 6, -, 7; of image 2 on 6, 5, 8.
  const std::vector<int> truth_a = {5, 6, -1, 7}, truth_b = {6, 5, 8};
  const std::vector<std::pair<int, int>> true_pairs = {{5, 5}, {6, 6}, {7, 7}, {8, 8}};
  const FeatureRecall r = CountRecall(truth_a, truth_b, true_pairs, {{0, 1}, {1, 2}, {2, 0}});
  EXPECT_EQ(r.seen_both, 2);  // 5 and 6; 7 and 8 are seen in one image only
  EXPECT_EQ(r.matched, 1);    // 5 (detections 0 and 1); 6 is joined to 8
}

TEST(MatchingEvaluationTest, SameTrueVertexAcceptsAnyCommonVertex) {
  EXPECT_EQ(SameTrueVertex({3, 4}, {4}), 1);
  EXPECT_EQ(SameTrueVertex({3}, {4, 5}), 0);
  EXPECT_EQ(SameTrueVertex({}, {4}), -1);
  EXPECT_EQ(SameTrueVertex({3}, {}), -1);
}

TEST(MatchingEvaluationTest, TrueVerticesNearJunctionsNearestFirst) {
  FrameTruth frame;
  for (auto [id, x] : {std::pair{10, 100.0}, std::pair{11, 102.0}, std::pair{12, 200.0}}) {
    VisibleVertex v;
    v.vertex = id;
    v.pixel = Eigen::Vector2d(x, 50);
    frame.vertices.push_back(v);
  }
  Junctions junctions(3);
  junctions[0].location = Eigen::Vector2d(101.8, 50);
  junctions[1].location = Eigen::Vector2d(150, 50);
  junctions[2].location = Eigen::Vector2d(199, 52);
  const std::vector<std::vector<int>> near = TrueVerticesNearJunctions(junctions, frame, 3.0);
  EXPECT_EQ(near[0], (std::vector<int>{11, 10}));
  EXPECT_TRUE(near[1].empty());
  EXPECT_EQ(near[2], (std::vector<int>{12}));
}

// Two L junctions at one vertex seen from two frames: a right match, a wrong one, and a vertex seen
// in both frames whose junctions differ in segment count.
TEST(MatchingEvaluationTest, ScoreVertexMatchesCountsPrecisionRecallAndReasons) {
  auto L = [](double x, double y) {
    Junction j;
    j.location = Eigen::Vector2d(x, y);
    j.segments = {{Eigen::Vector2d(x - 30, y), 0}, {Eigen::Vector2d(x, y - 30), 1}};
    return j;
  };
  Junctions a = {L(100, 100), L(300, 100), L(500, 300)};
  Junctions b = {L(90, 100), L(290, 100), L(490, 300)};
  b[2].segments.push_back({Eigen::Vector2d(520, 330), 2});  // a Y in image 2: never a candidate
  const std::vector<std::vector<int>> near_a = {{1}, {2}, {3}}, near_b = {{1}, {4}, {3}};
  const std::vector<JunctionMatch> matches = {{0, 0, 1.0, 0}, {1, 1, 1.0, 0}};
  const VertexMatchCounts c = ScoreVertexMatches(a, b, near_a, near_b, matches, SidewaysF(), MatchingOptions());
  EXPECT_EQ(c.matches, 2);
  EXPECT_EQ(c.associated, 2);
  EXPECT_EQ(c.same_vertex, 1);
  EXPECT_EQ(c.seen_both, 2);  // vertices 1 and 3
  EXPECT_EQ(c.seen_both_same_count, 1);
  EXPECT_EQ(c.matched, 1);
  EXPECT_EQ(c.misses[static_cast<int>(MissReason::kSegmentCount)], 1);
  EXPECT_EQ(c.matched_same_count, 1);
  EXPECT_EQ(c.matched_partial_only, 0);
}

// Partial matches in the recall columns: "recall, equal counts" counts only vertices joined by a
// full match, so it stays <= 100 % (before, every matched vertex was divided by the equal-count
// ones: 2 / 1 here); vertices joined by partial matches only are counted apart. Vertex 1: L-L, a
// full match; vertex 3: L against a Y, a partial match; vertex 5: L-L (equal counts) joined only
// by a partial match between another L and a Y also at it.
TEST(MatchingEvaluationTest, PartialMatchesAreCountedApartFromTheEqualCountRecall) {
  auto L = [](double x, double y) {
    Junction j;
    j.location = Eigen::Vector2d(x, y);
    j.segments = {{Eigen::Vector2d(x - 30, y), 0}, {Eigen::Vector2d(x, y - 30), 1}};
    return j;
  };
  auto Y = [&L](double x, double y) {
    Junction j = L(x, y);
    j.segments.push_back({Eigen::Vector2d(x + 30, y + 30), 2});
    return j;
  };
  const Junctions a = {L(100, 100), L(500, 300), L(300, 400), L(301, 401)};
  const Junctions b = {L(90, 100), Y(490, 300), L(290, 400), Y(291, 401)};
  const std::vector<std::vector<int>> near_a = {{1}, {3}, {5}, {5}}, near_b = {{1}, {3}, {5}, {5}};
  const std::vector<JunctionMatch> matches = {{0, 0, 1.0, 0}, {1, 1, 0.8, 0, -1, 2}, {3, 3, 0.8, 0, -1, 2}};
  ASSERT_TRUE(matches[1].Partial());
  const VertexMatchCounts c =
      ScoreVertexMatches(a, b, near_a, near_b, matches, SidewaysF(), MatchingOptions());
  EXPECT_EQ(c.seen_both, 3);
  EXPECT_EQ(c.seen_both_same_count, 2);  // vertices 1 and 5
  EXPECT_EQ(c.matched, 3);
  EXPECT_EQ(c.matched_same_count, 1);    // vertex 1
  EXPECT_EQ(c.matched_partial_only, 2);  // vertices 3 and 5
  EXPECT_LE(c.matched_same_count, c.seen_both_same_count);
}

TEST(MatchingEvaluationTest, AssociateSegmentsWantsTheSameLineAndOverlap) {
  const LineSegments truth = {Segment(0, 0, 100, 0), Segment(0, 50, 100, 50)};
  const LineSegments detected = {Segment(10, 1, 60, 1.5),    // on truth 0
                                 Segment(10, 4, 60, 4),      // 4 px off
                                 Segment(90, 0, 150, 0),     // overlaps 10 of 60 px
                                 Segment(10, 48.5, 60, 51)}; // on truth 1, 2.9 degrees
  EXPECT_EQ(AssociateSegments(detected, truth, LineAssociationOptions()), (std::vector<int>{0, -1, -1, 1}));
}

TEST(MatchingEvaluationTest, SegmentsEpipolarConsistentWantsTheBandsToMeet) {
  const Eigen::Matrix3d F = SidewaysF();  // epipolar lines: y = const
  const LineSegment vertical = Segment(100, 100, 100, 200);
  EXPECT_TRUE(SegmentsEpipolarConsistent(F, vertical, Segment(80, 150, 80, 260), 2.0));
  EXPECT_TRUE(SegmentsEpipolarConsistent(F, vertical, Segment(80, 201, 80, 260), 2.0));  // 1 px apart
  EXPECT_FALSE(SegmentsEpipolarConsistent(F, vertical, Segment(80, 205, 80, 260), 2.0));
}

TEST(MatchingEvaluationTest, WireframeLineIdsJoinCollinearEdges) {
  Wireframe w;
  w.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {5, 0, 0}, {6, 0, 0}};
  w.edges = {{0, 1, 0, -1}, {1, 2, 0, -1}, {2, 3, 0, -1}, {4, 5, 0, -1}};
  const std::vector<int> id = WireframeLineIds(w);
  EXPECT_EQ(id[0], id[1]);
  EXPECT_EQ(id[0], id[3]);  // on the same 3D line, though not touching
  EXPECT_NE(id[0], id[2]);
}

TEST(MatchingEvaluationTest, ProjectLineAndSegmentOnLine) {
  Eigen::Matrix<double, 3, 4> P;
  P << 500, 0, 320, 0, 0, 500, 240, 0, 0, 0, 1, 0;
  // The 3D line y = 0.2, z = 2 projects to image row 240 + 500 * 0.1 = 290.
  const Eigen::Vector3d line = ProjectLine(P, {-1, 0.2, 2}, {1, 0.2, 2});
  EXPECT_NEAR(line.dot(Eigen::Vector3d(10, 290, 1)), 0, 1e-9 * line.norm());
  const LineAssociationOptions options;
  EXPECT_TRUE(SegmentOnLine(Segment(100, 289, 300, 291), line, options));
  EXPECT_FALSE(SegmentOnLine(Segment(100, 289, 300, 295), line, options));
  EXPECT_FALSE(SegmentOnLine(Segment(300, 200, 300, 400), line, options));
}

TEST(MatchingEvaluationTest, LineMatchesJudgedByTheirThreeDLines) {
  const Eigen::Matrix3d F = SidewaysF();
  const LineSegments a = {Segment(100, 100, 100, 200), Segment(300, 100, 300, 200)};
  const LineSegments b = {Segment(80, 100, 80, 200), Segment(280, 100, 280, 200)};
  // 3D line 0 images at x = 100 (image 1) and x = 80 (image 2); line 1 at x = 300 and 280.
  const LineOfId in_a = [](int id) { return Eigen::Vector3d(1, 0, id == 0 ? -100 : -300); };
  const LineOfId in_b = [](int id) { return Eigen::Vector3d(1, 0, id == 0 ? -80 : -280); };
  // Segment 1 of image 2 is not on a known 3D line: the crossed match is still judged by the
  // image of line 0 in image 2.
  const LineMatchScore s = ScoreLineMatches(a, b, {{0, 0}, {0, 1}, {1, 1}}, {0, -1}, {0, -1}, in_a, in_b, F, 2.0);
  EXPECT_EQ(s.verdicts.matches, 3);
  EXPECT_EQ(s.verdicts.correct, 2);
  EXPECT_EQ(s.verdicts.identity_wrong, 1);
  EXPECT_EQ(s.verdicts.identity_known, 2);
  EXPECT_EQ(s.seen_both, 1);
  EXPECT_EQ(s.matched, 1);
}

TEST(MatchingEvaluationTest, ReadProjectionMatrixRejectsBadFiles) {
  const std::string dir = testing::MakeScratchDir("matching_evaluation_P");
  Eigen::Matrix<double, 3, 4> P;
  std::ofstream(dir + "/good.P") << "1 2 3 4\n5 6 7 8\n9 10 11 12\n";
  ASSERT_TRUE(ReadProjectionMatrix(dir + "/good.P", &P).ok());
  EXPECT_EQ(P(1, 2), 7);
  std::ofstream(dir + "/short.P") << "1 2 3 4\n5 6 7 8\n9 10 11\n";
  const Status s = ReadProjectionMatrix(dir + "/short.P", &P);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("short.P"), std::string::npos);
  EXPECT_FALSE(ReadProjectionMatrix(dir + "/missing.P", &P).ok());
}

// The shared VGG Corridor: identities read right, F of the P files agrees with the corner tracks,
// and LSD + LBD runs.
TEST(MatchingEvaluationTest, VggCorridorGroundTruth) {
  const std::string dir = testing::SharedDataDir("vgg-corridor");
  if (dir.empty()) GTEST_SKIP() << "../shared/data/vgg-corridor not present";
  VggTruth truth;
  ASSERT_TRUE(ReadVggTruth(dir, SegmentJunctionOptions(), &truth).ok());
  ASSERT_EQ(truth.views.size(), 11u);
  EXPECT_EQ(truth.lines3d.size(), 69u);
  // Corners on one bt.nview-corners track lie on each other's epipolar lines under F of the P's.
  std::vector<double> distances;
  const VggView& a = truth.views[0];
  const VggView& b = truth.views[1];
  const Eigen::Matrix3d F = FundamentalFromProjections(a.P, b.P);
  for (size_t i = 0; i < a.corners.size(); ++i) {
    if (a.corner_point3d[i] < 0) continue;
    for (size_t j = 0; j < b.corners.size(); ++j) {
      if (b.corner_point3d[j] == a.corner_point3d[i]) distances.push_back(SymmetricEpipolarDistance(F, a.corners[i], b.corners[j]));
    }
  }
  ASSERT_GT(distances.size(), 300u);
  EXPECT_LT(Quantile(distances, 0.5), 0.3);  // measured 0.12 px
  // Ground-truth segments on a bt.l3d line lie on its projection.
  int on_line = 0, identified = 0;
  for (size_t s = 0; s < a.lines.size(); ++s) {
    if (a.line3d[s] < 0) continue;
    ++identified;
    const auto& [X0, X1] = truth.lines3d[a.line3d[s]];
    on_line += SegmentOnLine(a.lines[s], ProjectLine(a.P, X0, X1), LineAssociationOptions());
  }
  ASSERT_GT(identified, 30);
  EXPECT_GE(on_line, identified - 1);
  // LSD + LBD on the first image: one descriptor row per segment.
  const cv::Mat image = cv::imread(dir + "/bt.000.pgm", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(image.empty());
  const LbdFeatures lbd = DetectLbd(image, 10.0);
  EXPECT_GT(lbd.segments.size(), 100u);
  EXPECT_EQ(lbd.descriptors.rows, static_cast<int>(lbd.segments.size()));
  const auto matches = MatchLbd(lbd.descriptors, lbd.descriptors, /*mutual=*/true);
  int self = 0;
  for (const auto& [i, j] : matches) self += i == j;
  EXPECT_GE(self, static_cast<int>(0.95 * lbd.segments.size()));  // an image matched with itself
}

}  // namespace
}  // namespace sfm
