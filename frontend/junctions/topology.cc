#include "frontend/junctions/topology.h"

#include <algorithm>
#include <map>
#include <vector>

namespace sfm {
namespace {

// The junction segment of `junction` from detected segment `line` that points most towards `toward`.
int SegmentToward(const Junction& junction, int line, const Eigen::Vector2d& toward) {
  int best = -1;
  double best_dot = 0;
  for (int i = 0; i < junction.NumSegments(); ++i) {
    if (junction.segments[i].line_segment != line) continue;
    const double dot = (junction.segments[i].end - junction.location).dot(toward - junction.location);
    if (best < 0 || dot > best_dot) {
      best = i;
      best_dot = dot;
    }
  }
  return best;
}

}  // namespace

TopologyGraph BuildTopologyGraph(const Junctions& junctions) {
  // Junctions using each detected segment, in order of first use.
  std::map<int, std::vector<int>> users;
  for (int j = 0; j < static_cast<int>(junctions.size()); ++j) {
    for (const JunctionSegment& segment : junctions[j].segments) {
      if (segment.line_segment < 0) continue;
      std::vector<int>& list = users[segment.line_segment];
      if (list.empty() || list.back() != j) list.push_back(j);
    }
  }

  TopologyGraph graph;
  graph.edges_of_junction.resize(junctions.size());
  for (auto& [line, list] : users) {
    if (list.size() < 2) continue;
    // Order along the line: by position along the direction from the first user to the farthest.
    const Eigen::Vector2d origin = junctions[list.front()].location;
    Eigen::Vector2d direction = Eigen::Vector2d::Zero();
    for (int j : list) {
      const Eigen::Vector2d d = junctions[j].location - origin;
      if (d.squaredNorm() > direction.squaredNorm()) direction = d;
    }
    std::stable_sort(list.begin(), list.end(), [&](int a, int b) {
      return (junctions[a].location - origin).dot(direction) <
             (junctions[b].location - origin).dot(direction);
    });
    for (size_t k = 0; k + 1 < list.size(); ++k) {
      const Junction& a = junctions[list[k]];
      const Junction& b = junctions[list[k + 1]];
      TopologyEdge edge;
      edge.junction_a = list[k];
      edge.segment_a = SegmentToward(a, line, b.location);
      edge.junction_b = list[k + 1];
      edge.segment_b = SegmentToward(b, line, a.location);
      graph.edges_of_junction[edge.junction_a].push_back(static_cast<int>(graph.edges.size()));
      graph.edges_of_junction[edge.junction_b].push_back(static_cast<int>(graph.edges.size()));
      graph.edges.push_back(edge);
    }
  }
  return graph;
}

}  // namespace sfm
