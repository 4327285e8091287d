#include "sequences/generator/wireframe.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace sfm {
namespace {

using VertexKey = std::array<long long, 3>;

// Vertices are merged on a 1 µm grid: the builder computes shared corners with identical
// arithmetic, so coincident vertices differ by a few ulp at most.
VertexKey KeyOf(const Eigen::Vector3d& p) {
  return {std::llround(p.x() * 1e6), std::llround(p.y() * 1e6), std::llround(p.z() * 1e6)};
}

bool SameLook(const Face& a, const Face& b) {
  return a.normal.dot(b.normal) > 1 - 1e-9 && a.albedo == b.albedo && a.emission == b.emission;
}

}  // namespace

Wireframe ExtractWireframe(const Scene& scene) {
  std::map<VertexKey, int> vertex_of_key;
  std::vector<Eigen::Vector3d> all_vertices;
  auto vertex_index = [&](const Eigen::Vector3d& p) {
    const auto [it, inserted] = vertex_of_key.emplace(KeyOf(p), static_cast<int>(all_vertices.size()));
    if (inserted) all_vertices.push_back(p);
    return it->second;
  };
  // Edge (sorted vertex pair) -> the faces it borders, in the order met.
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  std::vector<std::pair<int, int>> edge_order;
  for (int f = 0; f < static_cast<int>(scene.faces.size()); ++f) {
    const auto& polygon = scene.faces[f].vertices;
    for (size_t i = 0; i < polygon.size(); ++i) {
      int a = vertex_index(polygon[i]), b = vertex_index(polygon[(i + 1) % polygon.size()]);
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      auto& faces = faces_of_edge[{a, b}];
      if (faces.empty()) edge_order.push_back({a, b});
      faces.push_back(f);
    }
  }
  Wireframe wireframe;
  std::vector<int> new_index(all_vertices.size(), -1);
  auto keep_vertex = [&](int v) {
    if (new_index[v] < 0) {
      new_index[v] = static_cast<int>(wireframe.vertices.size());
      wireframe.vertices.push_back(all_vertices[v]);
    }
    return new_index[v];
  };
  for (const auto& key : edge_order) {
    const std::vector<int>& faces = faces_of_edge[key];
    if (faces.size() == 2 && SameLook(scene.faces[faces[0]], scene.faces[faces[1]])) continue;
    WireEdge edge;
    edge.vertex_a = keep_vertex(key.first);
    edge.vertex_b = keep_vertex(key.second);
    if (edge.vertex_a > edge.vertex_b) std::swap(edge.vertex_a, edge.vertex_b);
    edge.face_a = faces[0];
    edge.face_b = faces.size() > 1 ? faces[1] : -1;
    wireframe.edges.push_back(edge);
  }
  return wireframe;
}

}  // namespace sfm
