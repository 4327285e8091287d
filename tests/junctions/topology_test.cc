#include "frontend/junctions/topology.h"

#include <cmath>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "frontend/junctions/junction_detector.h"

namespace sfm {
namespace {

// The label of the vertex a junction sits on (within 1 px), or -1.
int VertexAt(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& vertices) {
  for (int v = 0; v < static_cast<int>(vertices.size()); ++v) {
    if ((p - vertices[v]).norm() < 1.0) return v;
  }
  return -1;
}

TEST(TopologyTest, CubeDrawing) {
  // A cube seen from a corner, drawn as segments stopping 2 px short of each vertex: the hexagon
  // outline 0..5 (0 at the top, clockwise) and the inner edges from the centre 6 to 0, 2 and 4.
  const Eigen::Vector2d center(200, 200);
  std::vector<Eigen::Vector2d> vertices;
  for (int k = 0; k < 6; ++k) {
    const double a = (-90 + 60 * k) * M_PI / 180;
    vertices.push_back(center + 100 * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  vertices.push_back(center);
  std::set<std::pair<int, int>> drawn;
  for (int k = 0; k < 6; ++k) drawn.insert({std::min(k, (k + 1) % 6), std::max(k, (k + 1) % 6)});
  for (int k : {0, 2, 4}) drawn.insert({k, 6});
  LineSegments segments;
  for (const auto& [a, b] : drawn) {
    const Eigen::Vector2d d = (vertices[b] - vertices[a]).normalized();
    LineSegment s;
    s.p0 = vertices[a] + 2 * d;
    s.p1 = vertices[b] - 2 * d;
    segments.push_back(s);
  }

  const Junctions junctions = DetectJunctions(segments, JunctionDetectorOptions());
  ASSERT_EQ(junctions.size(), 7u);
  std::vector<int> vertex_of;
  for (const Junction& j : junctions) {
    vertex_of.push_back(VertexAt(j.location, vertices));
    ASSERT_GE(vertex_of.back(), 0);
    const JunctionType expected = vertex_of.back() == 6       ? JunctionType::kY
                                  : vertex_of.back() % 2 == 0 ? JunctionType::kArrow
                                                              : JunctionType::kL;
    EXPECT_EQ(j.type, expected) << vertex_of.back();
  }

  const TopologyGraph graph = BuildTopologyGraph(junctions);
  // One edge per drawn segment, between the junctions at its two vertices.
  std::set<std::pair<int, int>> linked;
  for (const TopologyEdge& e : graph.edges) {
    const int a = vertex_of[e.junction_a], b = vertex_of[e.junction_b];
    linked.insert({std::min(a, b), std::max(a, b)});
    // Each side's junction segment runs along the shared segment towards the other junction.
    const Junction& ja = junctions[e.junction_a];
    const Junction& jb = junctions[e.junction_b];
    EXPECT_EQ(ja.segments[e.segment_a].line_segment, jb.segments[e.segment_b].line_segment);
    EXPECT_LT((ja.segments[e.segment_a].end - jb.location).norm(), 3.0);
    EXPECT_LT((jb.segments[e.segment_b].end - ja.location).norm(), 3.0);
  }
  EXPECT_EQ(graph.edges.size(), 9u);
  EXPECT_EQ(linked, drawn);
  ASSERT_EQ(graph.edges_of_junction.size(), junctions.size());
  for (size_t j = 0; j < junctions.size(); ++j) {
    EXPECT_EQ(static_cast<int>(graph.edges_of_junction[j].size()), junctions[j].NumSegments());
    for (int e : graph.edges_of_junction[j]) {
      EXPECT_TRUE(graph.edges[e].junction_a == static_cast<int>(j) ||
                  graph.edges[e].junction_b == static_cast<int>(j));
    }
  }
}

TEST(TopologyTest, BarWithTwoTsLinksNeighboursAlongIt) {
  // Bar 0 along y = 50 with L's at both ends (segments 1 and 4) and stems 2 and 3 making T's at
  // x = 30 and x = 70: along the bar, L(0) - T(30) - T(70) - L(100).
  LineSegments segments(5);
  segments[0].p0 = {0, 50}, segments[0].p1 = {100, 50};
  segments[1].p0 = {0, 100}, segments[1].p1 = {0, 52};
  segments[2].p0 = {30, 100}, segments[2].p1 = {30, 52};
  segments[3].p0 = {70, 0}, segments[3].p1 = {70, 48};
  segments[4].p0 = {100, 100}, segments[4].p1 = {100, 52};
  const Junctions junctions = DetectJunctions(segments, JunctionDetectorOptions());
  ASSERT_EQ(junctions.size(), 4u);
  const TopologyGraph graph = BuildTopologyGraph(junctions);
  ASSERT_EQ(graph.edges.size(), 3u);
  std::set<std::pair<double, double>> links;
  for (const TopologyEdge& e : graph.edges) {
    const double xa = junctions[e.junction_a].location.x(), xb = junctions[e.junction_b].location.x();
    links.insert({std::round(std::min(xa, xb)), std::round(std::max(xa, xb))});
    // The recorded junction segments face each other.
    const Eigen::Vector2d along = junctions[e.junction_b].location - junctions[e.junction_a].location;
    EXPECT_GT(junctions[e.junction_a].SegmentDirection(e.segment_a).dot(along), 0);
    EXPECT_LT(junctions[e.junction_b].SegmentDirection(e.segment_b).dot(along), 0);
  }
  EXPECT_EQ(links, (std::set<std::pair<double, double>>{{0, 30}, {30, 70}, {70, 100}}));
}

}  // namespace
}  // namespace sfm
