// evaluate_wireframe's figures on hand-built wireframes whose shares are known exactly.
#include "sfm_app/wireframe_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sfm {
namespace {

Wireframe TrueWireframe(const std::vector<Eigen::Vector3d>& vertices,
                        const std::vector<std::pair<int, int>>& edges) {
  Wireframe wireframe;
  wireframe.vertices = vertices;
  for (const auto& [a, b] : edges) {
    WireEdge edge;
    edge.vertex_a = a;
    edge.vertex_b = b;
    wireframe.edges.push_back(edge);
  }
  return wireframe;
}

// True edges: e0 (0,0,0)-(1,0,0) along the motion, e1 (5,0,0)-(5,0,1) vertical, both seen, and
// e2 (10,0,0)-(12,0,0) across, not seen. Samples every 2 cm sit at 0.01, 0.03, ... 0.99 m.
// Reconstructed: r0 3 cm beside e0 from x = 0 to 0.46 (covers the samples up to 0.49: 25 of 50,
// 0.50 m); r1 4 cm beside e1 from z = 0.505 to 2 (covers the samples from 0.49: 26 of 50, 0.52 m);
// r2 on e2 (not seen: no length counted); a lone vertex 20 cm from e0.
TEST(EvaluateWireframe, ExactSharesOnHandBuiltEdges) {
  const Wireframe truth = TrueWireframe({{0, 0, 0}, {1, 0, 0}, {5, 0, 0}, {5, 0, 1}, {10, 0, 0}, {12, 0, 0}},
                                        {{0, 1}, {2, 3}, {4, 5}});
  const std::vector<bool> seen = {true, true, false};
  const std::vector<EdgeDirection> direction = {EdgeDirection::kAlong, EdgeDirection::kVertical,
                                                EdgeDirection::kAcross};
  const std::vector<Eigen::Vector3d> vertices = {
      {0, 0.03, 0}, {0.46, 0.03, 0}, {5.04, 0, 0.505}, {5.04, 0, 2}, {0.5, 0.2, 0}, {10, 0, 0}, {12, 0, 0}};
  const std::vector<std::pair<int, int>> edges = {{0, 1}, {2, 3}, {5, 6}};
  const WireframeFigures figures =
      EvaluateWireframe(vertices, edges, truth, seen, direction, WireframeEvaluationOptions());

  // Precision: 5 of 7 vertices within 5 cm (not the far end of r1, not the lone vertex).
  EXPECT_EQ(figures.vertices, 7);
  EXPECT_EQ(figures.within, 5);
  EXPECT_NEAR(figures.precision, 5.0 / 7.0, 1e-12);
  EXPECT_EQ(figures.vertices_by_direction[0], 3);  // along: r0's ends and the lone vertex
  EXPECT_EQ(figures.within_by_direction[0], 2);
  EXPECT_EQ(figures.vertices_by_direction[2], 2);  // vertical: r1's ends
  EXPECT_EQ(figures.within_by_direction[2], 1);
  EXPECT_EQ(figures.vertices_by_direction[1], 2);  // across: r2's ends
  EXPECT_EQ(figures.within_by_direction[1], 2);

  // Completeness: (0.50 + 0.52) / 2 m; e2 is not seen and counts nowhere.
  EXPECT_NEAR(figures.seen_length_m, 2.0, 1e-12);
  EXPECT_NEAR(figures.covered_length_m, 1.02, 1e-12);
  EXPECT_NEAR(figures.completeness, 0.51, 1e-12);
  EXPECT_NEAR(figures.covered_length_by_direction[0] / figures.seen_length_by_direction[0], 0.50, 1e-12);
  EXPECT_NEAR(figures.covered_length_by_direction[2] / figures.seen_length_by_direction[2], 0.52, 1e-12);
  EXPECT_EQ(figures.seen_length_by_direction[1], 0.0);

  // Edge precision: r0 (0.46 m) and r2 (2 m) lie within 5 cm of a true edge; of r1 (1.495 m, z from
  // 0.505 to 2, 4 cm beside e1) the part up to z = 1.03 (4 cm beside, 3 cm above e1's top: 5 cm) is.
  // Pieces of r1: 75 of 1.495 / 75 m, midpoints at z = 0.505 + (i + 0.5) 0.019933: those up to 1.03,
  // i <= 25, are within (26 pieces).
  EXPECT_NEAR(figures.edge_length_m, 0.46 + 1.495 + 2, 1e-12);
  EXPECT_NEAR(figures.edge_within_m, 0.46 + 26 * 1.495 / 75 + 2, 1e-12);
}

// The in-view figures of the same wireframe: frames see e0 over t in [0, 0.6] (twice) and [0.1,
// 0.8], e1 over [0.25, 1], e2 (not seen: ignored) whole. In view: e0's samples 0.01-0.79 (40,
// 0.80 m; r0 covers 25 of them, 0.50 m) and e1's 0.25-0.99 (38, 0.76 m; r1 covers the 26 from
// 0.49). Ceiling 1.56 of 2 m; covered in view 1.02 m.
TEST(EvaluateWireframe, InViewLengthIsWhatSomeFrameSees) {
  const Wireframe truth = TrueWireframe({{0, 0, 0}, {1, 0, 0}, {5, 0, 0}, {5, 0, 1}, {10, 0, 0}, {12, 0, 0}},
                                        {{0, 1}, {2, 3}, {4, 5}});
  const std::vector<EdgeDirection> direction = {EdgeDirection::kAlong, EdgeDirection::kVertical,
                                                EdgeDirection::kAcross};
  const std::vector<Eigen::Vector3d> vertices = {{0, 0.03, 0}, {0.46, 0.03, 0}, {5.04, 0, 0.505}, {5.04, 0, 2}};
  const TrueEdgeViews views = {{{0, 0.6}, {0, 0.6}, {0.1, 0.8}}, {{0.25, 1}}, {{0, 1}}};
  const WireframeFigures figures = EvaluateWireframe(vertices, {{0, 1}, {2, 3}}, truth, {true, true, false},
                                                     direction, WireframeEvaluationOptions(), &views);
  EXPECT_NEAR(figures.seen_length_m, 2.0, 1e-12);
  EXPECT_NEAR(figures.in_view_length_m, 0.80 + 0.76, 1e-12);
  EXPECT_NEAR(figures.covered_in_view_length_m, 0.50 + 0.52, 1e-12);
  EXPECT_NEAR(figures.covered_length_m, 1.02, 1e-12);
  const WireframeFigures without = EvaluateWireframe(vertices, {{0, 1}, {2, 3}}, truth, {true, true, false},
                                                     direction, WireframeEvaluationOptions());
  EXPECT_EQ(without.in_view_length_m, 0.0);
}

// Points alone cover nothing; an edge lying on a true edge covers all of it; nothing seen: NaN.
TEST(EvaluateWireframe, PointsAloneAreNotComplete) {
  const Wireframe truth = TrueWireframe({{0, 0, 0}, {0.3, 0, 0}}, {{0, 1}});
  const std::vector<EdgeDirection> direction = {EdgeDirection::kAcross};
  const WireframeEvaluationOptions options;
  const std::vector<Eigen::Vector3d> vertices = {{0, 0, 0}, {0.3, 0, 0}};
  EXPECT_EQ(EvaluateWireframe(vertices, {}, truth, {true}, direction, options).completeness, 0.0);
  EXPECT_NEAR(EvaluateWireframe(vertices, {{0, 1}}, truth, {true}, direction, options).completeness, 1.0,
              1e-12);
  EXPECT_TRUE(
      std::isnan(EvaluateWireframe(vertices, {{0, 1}}, truth, {false}, direction, options).completeness));
}

// Three frames moving along +x. Vertex 0 is seen in all three, vertex 1 in two, vertex 2 in one.
TEST(SeenAndClassifiedTrueEdges, ByViewsAndByMotion) {
  GroundTruth truth;
  truth.wireframe =
      TrueWireframe({{0, 5, 0}, {3, 5, 0}, {3, 8, 0}, {3, 8, 2}, {0, 6, 0}, {0, 7, 0}, {0, 7, 1}},
                    {{0, 1}, {1, 2}, {2, 3}, {0, 4}, {4, 5}, {5, 6}});
  // Extra edges in the horizontal plane at 44 and 46 degrees from the motion, and one at 46 degrees
  // from the horizontal (vertical).
  const double to_rad = M_PI / 180;
  const auto add = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    truth.wireframe.vertices.push_back(from);
    truth.wireframe.vertices.push_back(to);
    WireEdge edge;
    edge.vertex_a = static_cast<int>(truth.wireframe.vertices.size()) - 2;
    edge.vertex_b = edge.vertex_a + 1;
    truth.wireframe.edges.push_back(edge);
  };
  add({0, 0, 0}, {std::cos(44 * to_rad), std::sin(44 * to_rad), 0});
  add({0, 0, 0}, {std::cos(46 * to_rad), std::sin(46 * to_rad), 0});
  add({0, 0, 0}, {std::cos(46 * to_rad), 0, std::sin(46 * to_rad)});
  for (int f = 0; f < 3; ++f) {
    FrameTruth frame;
    frame.index = f;
    frame.world_T_camera = Pose3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(f, 0, 1));
    for (const int v : {0, 1, 2}) {
      if ((v == 1 && f == 2) || (v == 2 && f != 2)) continue;
      VisibleVertex visible;
      visible.vertex = v;
      frame.vertices.push_back(visible);
    }
    truth.frames.push_back(frame);
  }
  const std::vector<bool> seen = SeenTrueEdges(truth, 3);
  EXPECT_EQ(seen, (std::vector<bool>{true, false, false, true, false, false, false, false, false}));
  EXPECT_EQ(SeenTrueEdges(truth, 2)[1], true);
  const std::vector<EdgeDirection> direction = ClassifyTrueEdges(truth);
  const std::vector<EdgeDirection> expected = {
      EdgeDirection::kAlong,  EdgeDirection::kAcross, EdgeDirection::kVertical,
      EdgeDirection::kAcross, EdgeDirection::kAcross, EdgeDirection::kVertical,
      EdgeDirection::kAlong,  EdgeDirection::kAcross, EdgeDirection::kVertical};
  EXPECT_EQ(direction, expected);
}

}  // namespace
}  // namespace sfm
