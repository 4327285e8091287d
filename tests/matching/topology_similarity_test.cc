// Section 4.2: sigma on hand-built topology graphs with hand-chosen rho values.
#include "frontend/matching/topology_similarity.h"

#include <map>
#include <utility>

#include <gtest/gtest.h>

namespace sfm {
namespace {

// Junctions whose geometry the test never looks at: only their segment counts matter here.
Junctions Dummies(int count, int num_segments) {
  Junction junction;
  for (int k = 0; k < num_segments; ++k) junction.segments.push_back({Eigen::Vector2d(k + 1, 0), -1});
  return Junctions(count, junction);
}

void AddEdge(TopologyGraph* graph, int junction_a, int segment_a, int junction_b, int segment_b) {
  graph->edges.push_back({junction_a, segment_a, junction_b, segment_b});
  graph->edges_of_junction[junction_a].push_back(static_cast<int>(graph->edges.size()) - 1);
  graph->edges_of_junction[junction_b].push_back(static_cast<int>(graph->edges.size()) - 1);
}

// rho values by hand; unlisted pairs are unmatched.
using HandRho = std::map<std::pair<int, int>, PairSimilarity>;
SimilarityTable::Evaluator FromMap(const HandRho* values) {
  return [values](int a, int b) {
    const auto it = values->find({a, b});
    return it == values->end() ? PairSimilarity() : it->second;
  };
}

// Two boxes per image, each drawn as four L junctions (corners) joined by its four sides. In image
// 1 corner c of box k is junction 4k + c; its segment 0 runs to the next corner, segment 1 to the
// previous one. Image 2 numbers the junctions differently (kOfA) and numbers corner 1's segments
// the other way round (so its pair has shift 1).
class TwoBoxesTest : public ::testing::Test {
 protected:
  static constexpr int kOfA[8] = {5, 6, 7, 4, 1, 2, 3, 0};

  void SetUp() override {
    a_ = Dummies(8, 2);
    b_ = Dummies(8, 2);
    graph_a_.edges_of_junction.resize(8);
    graph_b_.edges_of_junction.resize(8);
    for (int box = 0; box < 2; ++box) {
      for (int c = 0; c < 4; ++c) {
        const int from = 4 * box + c, to = 4 * box + (c + 1) % 4;
        AddEdge(&graph_a_, from, 0, to, 1);
        AddEdge(&graph_b_, kOfA[from], SegmentInB(from, 0), kOfA[to], SegmentInB(to, 1));
      }
    }
    const double rho[8] = {0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2};
    for (int j = 0; j < 8; ++j) rho_[{j, kOfA[j]}] = {rho[j], j % 4 == 1 ? 1 : 0};
  }
  static int SegmentInB(int junction_a, int segment) { return junction_a % 4 == 1 ? 1 - segment : segment; }

  double Sigma(int a, int b) {
    SimilarityTable table(8, 8, FromMap(&rho_));
    TopologySimilarity topology(a_, graph_a_, b_, graph_b_, &table);
    return topology.Sigma(a, b);
  }

  Junctions a_, b_;
  TopologyGraph graph_a_, graph_b_;
  HandRho rho_;
};

TEST_F(TwoBoxesTest, SigmaSumsEveryMappedSideOfTheBox) {
  // From corner 0 of box 0: sides 0-1 and 3-0 first (both counted), then 1-2 from corner 1 and
  // 2-3 from corner 2 (or 3): each side adds 0.5 (rho of its two corners), so sigma is the sum of
  // the corners' rho: 0.9 + 0.8 + 0.7 + 0.6 = 3.0. Box 1 is another component: 0.5+0.4+0.3+0.2.
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(Sigma(c, kOfA[c]), 3.0, 1e-12) << c;
  for (int c = 4; c < 8; ++c) EXPECT_NEAR(Sigma(c, kOfA[c]), 1.4, 1e-12) << c;
}

TEST_F(TwoBoxesTest, AnInconsistentShiftBreaksThePlausibleMappings) {
  // Corner 2's pair with the wrong segment correspondence: sides 1-2 and 2-3 are not plausible.
  // From corner 0: 0.5 (0.9 + 0.8) + 0.5 (0.9 + 0.6) = 1.6; from corner 2 nothing maps: sigma = rho.
  rho_[{2, kOfA[2]}].shift = 1;
  EXPECT_NEAR(Sigma(0, kOfA[0]), 1.6, 1e-12);
  EXPECT_NEAR(Sigma(2, kOfA[2]), 0.7, 1e-12);
}

TEST_F(TwoBoxesTest, UnmatchedPairHasZeroSigma) {
  EXPECT_EQ(Sigma(0, kOfA[1]), 0);
  // Corners of the other box have no plausible mapping: sigma = rho = 0.
  EXPECT_EQ(Sigma(0, kOfA[4]), 0);
}

TEST(TopologySimilarityTest, SigmaIsRhoWithoutEdges) {
  const Junctions a = Dummies(3, 2), b = Dummies(2, 2);
  TopologyGraph graph_a, graph_b;
  graph_a.edges_of_junction.resize(3);
  graph_b.edges_of_junction.resize(2);
  const HandRho rho = {{{0, 0}, {0.83, 1}}, {{2, 1}, {0.41, 0}}};
  SimilarityTable table(3, 2, FromMap(&rho));
  TopologySimilarity topology(a, graph_a, b, graph_b, &table);
  EXPECT_EQ(topology.Sigma(0, 0), 0.83);
  EXPECT_EQ(topology.Sigma(2, 1), 0.41);
  EXPECT_EQ(topology.Sigma(1, 1), 0);
}

TEST(TopologySimilarityTest, GreedyMappingTakesTheLargerRho) {
  // Junction 0 of image 1 lies on a line segment that also holds junctions 1 and 2 (two edges from
  // its segment 0); in image 2 junction 0's segment 0 reaches junction 1 only. Both mappings are
  // plausible; (35) takes the one whose far pair has the larger rho: (2, 1) with 0.7 over (1, 1)
  // with 0.5. sigma = 0.5 (0.9 + 0.7).
  const Junctions a = Dummies(3, 2), b = Dummies(2, 2);
  TopologyGraph graph_a, graph_b;
  graph_a.edges_of_junction.resize(3);
  graph_b.edges_of_junction.resize(2);
  AddEdge(&graph_a, 0, 0, 1, 1);
  AddEdge(&graph_a, 0, 0, 2, 1);
  AddEdge(&graph_b, 0, 0, 1, 1);
  HandRho rho = {{{0, 0}, {0.9, 0}}, {{1, 1}, {0.5, 0}}, {{2, 1}, {0.7, 0}}};
  {
    SimilarityTable table(3, 2, FromMap(&rho));
    TopologySimilarity topology(a, graph_a, b, graph_b, &table);
    EXPECT_NEAR(topology.Sigma(0, 0), 0.8, 1e-12);
  }
  rho[{1, 1}].rho = 0.75;
  SimilarityTable table(3, 2, FromMap(&rho));
  TopologySimilarity topology(a, graph_a, b, graph_b, &table);
  EXPECT_NEAR(topology.Sigma(0, 0), 0.825, 1e-12);
}

}  // namespace
}  // namespace sfm
