// Junctions (paper section 2.2): line segments meeting at a point, and the topology graph that
// links junctions sharing a line segment (section 4.2).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace sfm {

// The junction detector's location error on rendered images, pixels: its 90th percentile (0.27 px;
// median 0.16 px; docs/junctions.md, "Checks against rendered images"). The pixel noise of a
// junction location where the back end tests observations against it.
inline constexpr double kJunctionLocationErrorPx = 0.3;

enum class JunctionType { kL, kY, kArrow, kT, kX, kN };

// "L", "Y", "ARROW", "T", "X", "N" as SPEC section 3 writes them.
const char* JunctionTypeName(JunctionType type);

struct JunctionSegment {
  Eigen::Vector2d end = Eigen::Vector2d::Zero();  // far end-point p_i, pixels
  int line_segment = -1;  // index of the detected LineSegment it comes from (a T's bar gives two)
};

struct Junction {
  int id = 0;                                          // unique within the frame
  Eigen::Vector2d location = Eigen::Vector2d::Zero();  // p0, pixels of the undistorted image
  JunctionType type = JunctionType::kL;
  double score = 0;                       // junction probability (sum of pairwise f-products)
  std::vector<JunctionSegment> segments;  // clockwise as seen in the image (y down)

  int NumSegments() const { return static_cast<int>(segments.size()); }
  // Unit direction of junction segment i, from p0 towards its end-point.
  Eigen::Vector2d SegmentDirection(int i) const { return (segments[i].end - location).normalized(); }
};

using Junctions = std::vector<Junction>;

// An edge of the topology graph: junctions a and b both use one detected line segment, as their
// junction segments segment_a and segment_b.
struct TopologyEdge {
  int junction_a = -1, segment_a = -1;
  int junction_b = -1, segment_b = -1;
};

// Topology graph of one image: edges, and for each junction (by index into Junctions) the indices
// of the edges touching it.
struct TopologyGraph {
  std::vector<TopologyEdge> edges;
  std::vector<std::vector<int>> edges_of_junction;
};

}  // namespace sfm
