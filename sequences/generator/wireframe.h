// Wireframe: the scene's polygon borders that are real image edges, as a 3D line graph.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sequences/generator/scene.h"

namespace sfm {

struct WireEdge {
  int vertex_a = -1, vertex_b = -1;  // indices into Wireframe::vertices, vertex_a < vertex_b
  int face_a = -1, face_b = -1;      // faces bordered by the edge (face_b = -1: only one)
};

struct Wireframe {
  std::vector<Eigen::Vector3d> vertices;  // world, m
  std::vector<WireEdge> edges;
};

// The scene's wireframe. Polygon vertices closer than 1e-6 m are merged; each polygon side becomes
// an edge between its merged end-points, and a side shared by several faces is one edge. An edge
// is kept when it is a real image edge: its faces differ in orientation or albedo (or it borders
// a single face, such as a poster on a wall). The scene builder guarantees that such faces differ
// in brightness. Vertices on no kept edge are dropped; vertices and edges come in a fixed order.
Wireframe ExtractWireframe(const Scene& scene);

}  // namespace sfm
