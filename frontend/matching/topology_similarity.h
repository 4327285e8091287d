// Similarity of two junctions from their junction topology, sigma(J, J') (paper section 4.2, eq.
// 35 and the stack traversal after it).
#pragma once

#include <vector>

#include "frontend/junctions/junction.h"
#include "frontend/matching/similarity_table.h"

namespace sfm {

class TopologySimilarity {
 public:
  // graph_a/graph_b: topology graphs of junctions a/b; table: rho of every pair (a, b). Keeps
  // references to all five. Self-loops (a junction sharing a line segment with itself) are ignored.
  TopologySimilarity(const Junctions& a, const TopologyGraph& graph_a, const Junctions& b,
                     const TopologyGraph& graph_b, SimilarityTable* table);

  // sigma(J, J'): traverse G_J and G_J' together from (J, J') with a stack, mapping the unmapped
  // edges at each reached pair of vertices by C of (35); each mapped pair <Ja Jb, J'a J'b> adds
  // 0.5 (rho(Ja, J'a) + rho(Jb, J'b)), the first ones included (ALGORITHM.md 4.2). sigma = rho
  // when C(E_J, E_J') is empty.
  double Sigma(int index_a, int index_b);

 private:
  // Edge `edge` seen from `vertex`: the segment it uses there and the junction at its other end.
  struct EdgeEnd {
    int near_segment;
    int far_vertex;
    int far_segment;
  };
  static EdgeEnd EndFrom(const TopologyEdge& edge, int vertex);

  // A plausible mapping of edge_a (leaving vertex_a) onto edge_b (leaving vertex_b).
  struct EdgeMapping {
    int edge_a, edge_b;
    int far_a, far_b;
    double far_rho;  // rho(far_a, far_b): what (35) compares
  };
  // Eq. (35): C(E_Ja, E_J'b), the greedy one-to-one mapping of the unmapped edges at vertex_a and
  // vertex_b; marks the mapped edges. A mapping is plausible when rho > 0 at both ends and both
  // maximising shifts pair the shared segment of one edge with that of the other.
  void MapEdges(int vertex_a, int vertex_b, std::vector<EdgeMapping>* mapped);

  const Junctions& a_;
  const TopologyGraph& graph_a_;
  const Junctions& b_;
  const TopologyGraph& graph_b_;
  SimilarityTable* table_;
  // Edge e is mapped in the current Sigma call when its stamp equals stamp_ (no clearing per call).
  std::vector<unsigned> mapped_a_;
  std::vector<unsigned> mapped_b_;
  unsigned stamp_ = 0;
  // Scratch, kept across calls.
  struct VertexPair {
    int a, b;
    double rho;  // rho(a, b)
  };
  std::vector<EdgeMapping> candidates_;
  std::vector<EdgeMapping> mapped_;
  std::vector<VertexPair> stack_;
};

}  // namespace sfm
