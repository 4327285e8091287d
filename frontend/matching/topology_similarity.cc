#include "frontend/matching/topology_similarity.h"

#include <algorithm>

#include <glog/logging.h>

namespace sfm {

TopologySimilarity::TopologySimilarity(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                                       const TopologyGraph& graph_b, SimilarityTable* table)
    : a_(a), graph_a_(graph_a), b_(b), graph_b_(graph_b), table_(table),
      mapped_a_(graph_a.edges.size(), 0), mapped_b_(graph_b.edges.size(), 0) {
  CHECK_EQ(graph_a.edges_of_junction.size(), a.size());
  CHECK_EQ(graph_b.edges_of_junction.size(), b.size());
  CHECK_EQ(table->num_a(), static_cast<int>(a.size()));
  CHECK_EQ(table->num_b(), static_cast<int>(b.size()));
  for (const TopologyGraph* graph : {&graph_a, &graph_b}) {
    const int num_junctions = static_cast<int>(graph->edges_of_junction.size());
    for (const TopologyEdge& edge : graph->edges) {
      CHECK(edge.junction_a >= 0 && edge.junction_a < num_junctions && edge.junction_b >= 0 &&
            edge.junction_b < num_junctions)
          << "topology edge between junctions " << edge.junction_a << " and " << edge.junction_b;
    }
  }
}

TopologySimilarity::EdgeEnd TopologySimilarity::EndFrom(const TopologyEdge& edge, int vertex) {
  if (edge.junction_a == vertex) return {edge.segment_a, edge.junction_b, edge.segment_b};
  return {edge.segment_b, edge.junction_a, edge.segment_a};
}

void TopologySimilarity::MapEdges(int vertex_a, int vertex_b, std::vector<EdgeMapping>* mapped) {
  mapped->clear();
  const PairSimilarity& near = table_->Get(vertex_a, vertex_b);
  if (!near.Matched() || near.rho <= 0) return;
  const int n_near = a_[vertex_a].NumSegments();
  candidates_.clear();
  for (const int edge_a : graph_a_.edges_of_junction[vertex_a]) {
    const TopologyEdge& ea = graph_a_.edges[edge_a];
    if (mapped_a_[edge_a] == stamp_ || ea.junction_a == ea.junction_b) continue;
    const EdgeEnd end_a = EndFrom(ea, vertex_a);
    for (const int edge_b : graph_b_.edges_of_junction[vertex_b]) {
      const TopologyEdge& eb = graph_b_.edges[edge_b];
      if (mapped_b_[edge_b] == stamp_ || eb.junction_a == eb.junction_b) continue;
      const EdgeEnd end_b = EndFrom(eb, vertex_b);
      // The shared segment must be paired at the near end by rho(vertex_a, vertex_b) ...
      if (end_b.near_segment != (end_a.near_segment + near.shift) % n_near) continue;
      const PairSimilarity& far = table_->Get(end_a.far_vertex, end_b.far_vertex);
      if (!far.Matched() || far.rho <= 0) continue;
      // ... and at the far end by rho(far_a, far_b).
      const int n_far = a_[end_a.far_vertex].NumSegments();
      if (end_b.far_segment != (end_a.far_segment + far.shift) % n_far) continue;
      candidates_.push_back({edge_a, edge_b, end_a.far_vertex, end_b.far_vertex, far.rho});
    }
  }
  // (35) adds a mapping whose rho no other plausible mapping sharing one of its edges exceeds, then
  // recurses on the rest: taking the mappings in decreasing rho, each edge once, is that recursion
  // (ties broken by edge index, so the result does not depend on the order of the lists).
  std::sort(candidates_.begin(), candidates_.end(), [](const EdgeMapping& x, const EdgeMapping& y) {
    if (x.far_rho != y.far_rho) return x.far_rho > y.far_rho;
    if (x.edge_a != y.edge_a) return x.edge_a < y.edge_a;
    return x.edge_b < y.edge_b;
  });
  for (const EdgeMapping& candidate : candidates_) {
    if (mapped_a_[candidate.edge_a] == stamp_ || mapped_b_[candidate.edge_b] == stamp_) continue;
    mapped_a_[candidate.edge_a] = stamp_;
    mapped_b_[candidate.edge_b] = stamp_;
    mapped->push_back(candidate);
  }
}

double TopologySimilarity::Sigma(int index_a, int index_b) {
  ++stamp_;
  if (stamp_ == 0) {  // wrapped: stale stamps could equal the new one
    std::fill(mapped_a_.begin(), mapped_a_.end(), 0);
    std::fill(mapped_b_.begin(), mapped_b_.end(), 0);
    stamp_ = 1;
  }
  const double rho = table_->Get(index_a, index_b).rho;
  MapEdges(index_a, index_b, &mapped_);
  if (mapped_.empty()) return rho;
  stack_.clear();
  double sigma = 0;
  VertexPair current{index_a, index_b, rho};
  while (true) {
    for (const EdgeMapping& mapping : mapped_) {
      sigma += 0.5 * (current.rho + mapping.far_rho);
      stack_.push_back({mapping.far_a, mapping.far_b, mapping.far_rho});
    }
    if (stack_.empty()) break;
    current = stack_.back();
    stack_.pop_back();
    MapEdges(current.a, current.b, &mapped_);
  }
  return sigma;
}

}  // namespace sfm
