// How close a reconstructed wireframe lies to a generated sequence's true one, and how much of the
// true one it covers (evaluate_wireframe; definitions in docs/metrics.md, "Wireframe").
//
// Precision: the share of reconstructed vertices within `threshold_m` of a true edge (a 3D segment).
// Completeness: the share of the length of the true edges seen from the cameras that lies within
// `threshold_m` of a reconstructed edge, measured at samples every `sample_step_m` along each true
// edge. A true edge is seen when one of its vertices is visible in at least `min_views` frames.
// Both figures are also given per direction of the true edge: along the robot's motion, across it,
// vertical. Edge precision: the share of the reconstructed edges' length within `threshold_m` of a
// true edge (a wrong join between two good vertices lowers it, not the vertex precision).
#pragma once

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

#include "sequences/generator/ground_truth.h"

namespace sfm {

enum class EdgeDirection { kAlong = 0, kAcross = 1, kVertical = 2 };
inline constexpr int kEdgeDirections = 3;
const char* EdgeDirectionName(EdgeDirection direction);  // "along", "across", "vertical"

struct WireframeEvaluationOptions {
  double threshold_m = 0.05;    // a vertex within this of a true edge, a sample within this of an edge
  double sample_step_m = 0.02;  // spacing of the samples along a true edge
  int min_views = 3;            // frames that must see one of a true edge's vertices for it to count
};

// Per true edge (truth.wireframe.edges order): whether a vertex of it is visible in at least
// `min_views` frames of truth.frames.
std::vector<bool> SeenTrueEdges(const GroundTruth& truth, int min_views);

// Per true edge: the part of it each frame sees, [t0, t1] along it (truth.frames' visible
// segments, occlusion and the image border taken out), one entry per visible segment.
using TrueEdgeViews = std::vector<std::vector<std::pair<double, double>>>;
TrueEdgeViews ViewsOfTrueEdges(const GroundTruth& truth);

// Per true edge: vertical when its direction is more than 45 degrees from the horizontal (world z is
// up, docs/conventions.md); otherwise along the motion when, summed over the frames that see one of
// its vertices (all frames when none does), the components of the camera's motion at each frame
// (true centre of the next frame minus that of the previous one, in the horizontal plane) along
// the edge outweigh those across it; across otherwise (also when the camera does not move).
std::vector<EdgeDirection> ClassifyTrueEdges(const GroundTruth& truth);

struct WireframeFigures {
  int vertices = 0;
  int within = 0;        // vertices within threshold_m of a true edge
  double precision = 0;  // within / vertices (NaN without vertices)
  double median_m = 0;   // of the vertices' distances to the nearest true edge (NaN without vertices)
  double p90_m = 0;
  double seen_length_m = 0;     // total length of the seen true edges
  double covered_length_m = 0;  // of it, the length within threshold_m of a reconstructed edge
  double completeness = 0;      // covered / seen (NaN when nothing is seen)
  // Of the seen length, the part some frame sees (EvaluateWireframe's `views`; 0 without them):
  // what a reconstruction from these frames can cover, the completeness' ceiling (but for the
  // threshold's slack at the ends); and of it, the length within threshold_m of a reconstructed edge.
  double in_view_length_m = 0;
  double covered_in_view_length_m = 0;
  double edge_length_m = 0;     // total length of the reconstructed edges
  double edge_within_m = 0;     // of it, the length within threshold_m of a true edge
  double edge_precision = 0;    // edge_within / edge_length (NaN without edges of positive length)
  // Per EdgeDirection: vertices by the direction of their nearest true edge, lengths by their edge's.
  std::array<int, kEdgeDirections> vertices_by_direction{}, within_by_direction{};
  std::array<double, kEdgeDirections> seen_length_by_direction{}, covered_length_by_direction{};
};

// The figures of a reconstructed wireframe (vertices, edges as index pairs into them) against
// `truth`, with `seen` and `direction` per true edge (SeenTrueEdges, ClassifyTrueEdges; CHECKed to
// have one entry per edge). An edge of length L (true, or reconstructed for the edge precision) is
// sampled at the midpoints of ceil(L / step) equal pieces, each standing for its piece's length.
// `views` (ViewsOfTrueEdges, one entry per edge, CHECKed), when given, sets the in-view figures.
WireframeFigures EvaluateWireframe(const std::vector<Eigen::Vector3d>& vertices,
                                   const std::vector<std::pair<int, int>>& edges, const Wireframe& truth,
                                   const std::vector<bool>& seen, const std::vector<EdgeDirection>& direction,
                                   const WireframeEvaluationOptions& options,
                                   const TrueEdgeViews* views = nullptr);

// Distance from p to the segment ab (to a when a == b).
double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace sfm
