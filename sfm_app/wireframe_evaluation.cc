#include "sfm_app/wireframe_evaluation.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sfm {

const char* EdgeDirectionName(EdgeDirection direction) {
  switch (direction) {
    case EdgeDirection::kAlong:
      return "along";
    case EdgeDirection::kAcross:
      return "across";
    case EdgeDirection::kVertical:
      return "vertical";
  }
  return "?";
}

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

namespace {

// views[v]: the frames in which true vertex v is visible.
std::vector<std::vector<int>> FramesSeeingVertex(const GroundTruth& truth) {
  std::vector<std::vector<int>> views(truth.wireframe.vertices.size());
  for (size_t f = 0; f < truth.frames.size(); ++f) {
    for (const VisibleVertex& visible : truth.frames[f].vertices) {
      if (visible.vertex >= 0 && visible.vertex < static_cast<int>(views.size())) {
        views[visible.vertex].push_back(static_cast<int>(f));
      }
    }
  }
  return views;
}

}  // namespace

std::vector<bool> SeenTrueEdges(const GroundTruth& truth, int min_views) {
  const std::vector<std::vector<int>> views = FramesSeeingVertex(truth);
  std::vector<bool> seen;
  seen.reserve(truth.wireframe.edges.size());
  for (const WireEdge& edge : truth.wireframe.edges) {
    seen.push_back(static_cast<int>(views[edge.vertex_a].size()) >= min_views ||
                   static_cast<int>(views[edge.vertex_b].size()) >= min_views);
  }
  return seen;
}

TrueEdgeViews ViewsOfTrueEdges(const GroundTruth& truth) {
  TrueEdgeViews views(truth.wireframe.edges.size());
  for (const FrameTruth& frame : truth.frames) {
    for (const VisibleSegment& segment : frame.segments) {
      if (segment.edge >= 0 && segment.edge < static_cast<int>(views.size()))
        views[segment.edge].emplace_back(segment.t[0], segment.t[1]);
    }
  }
  return views;
}

std::vector<EdgeDirection> ClassifyTrueEdges(const GroundTruth& truth) {
  const std::vector<std::vector<int>> views = FramesSeeingVertex(truth);
  const int frames = static_cast<int>(truth.frames.size());
  // The camera's horizontal motion at each frame: central difference of the true centres.
  std::vector<Eigen::Vector2d> motion(frames, Eigen::Vector2d::Zero());
  for (int f = 0; f < frames && frames >= 2; ++f) {
    const Eigen::Vector3d step = truth.frames[std::min(f + 1, frames - 1)].world_T_camera.translation -
                                 truth.frames[std::max(f - 1, 0)].world_T_camera.translation;
    motion[f] = step.head<2>();
  }
  std::vector<EdgeDirection> directions;
  directions.reserve(truth.wireframe.edges.size());
  for (const WireEdge& edge : truth.wireframe.edges) {
    const Eigen::Vector3d d =
        (truth.wireframe.vertices[edge.vertex_b] - truth.wireframe.vertices[edge.vertex_a]).normalized();
    if (std::abs(d.z()) > std::sqrt(0.5)) {
      directions.push_back(EdgeDirection::kVertical);
      continue;
    }
    const Eigen::Vector2d h = d.head<2>().normalized();
    std::vector<int> seeing = views[edge.vertex_a];
    seeing.insert(seeing.end(), views[edge.vertex_b].begin(), views[edge.vertex_b].end());
    std::sort(seeing.begin(), seeing.end());
    seeing.erase(std::unique(seeing.begin(), seeing.end()), seeing.end());
    if (seeing.empty()) {
      for (int f = 0; f < frames; ++f) seeing.push_back(f);
    }
    double along = 0, across = 0;
    for (const int f : seeing) {
      along += std::abs(h.dot(motion[f]));
      across += std::abs(h.x() * motion[f].y() - h.y() * motion[f].x());
    }
    directions.push_back(along > across ? EdgeDirection::kAlong : EdgeDirection::kAcross);
  }
  return directions;
}

WireframeFigures EvaluateWireframe(const std::vector<Eigen::Vector3d>& vertices,
                                   const std::vector<std::pair<int, int>>& edges, const Wireframe& truth,
                                   const std::vector<bool>& seen, const std::vector<EdgeDirection>& direction,
                                   const WireframeEvaluationOptions& options, const TrueEdgeViews* views) {
  CHECK_EQ(seen.size(), truth.edges.size());
  if (views != nullptr) CHECK_EQ(views->size(), truth.edges.size());
  CHECK_EQ(direction.size(), truth.edges.size());
  CHECK_GT(options.sample_step_m, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  WireframeFigures figures;

  // Precision: each vertex against its nearest true edge.
  figures.vertices = static_cast<int>(vertices.size());
  std::vector<double> distances;
  distances.reserve(vertices.size());
  for (const Eigen::Vector3d& p : vertices) {
    double best = std::numeric_limits<double>::infinity();
    int nearest = -1;
    for (size_t e = 0; e < truth.edges.size(); ++e) {
      const double distance = DistanceToSegment(p, truth.vertices[truth.edges[e].vertex_a],
                                                truth.vertices[truth.edges[e].vertex_b]);
      if (distance < best) {
        best = distance;
        nearest = static_cast<int>(e);
      }
    }
    distances.push_back(best);
    const bool within = best <= options.threshold_m;
    figures.within += within;
    if (nearest >= 0) {
      const int k = static_cast<int>(direction[nearest]);
      ++figures.vertices_by_direction[k];
      figures.within_by_direction[k] += within;
    }
  }
  figures.precision = figures.median_m = figures.p90_m = nan;
  if (!distances.empty()) {
    figures.precision = static_cast<double>(figures.within) / distances.size();
    std::sort(distances.begin(), distances.end());
    figures.median_m = distances[distances.size() / 2];
    figures.p90_m = distances[std::min(distances.size() - 1, static_cast<size_t>(0.9 * distances.size()))];
  }

  // Completeness: samples along the seen true edges against the reconstructed edges.
  for (size_t e = 0; e < truth.edges.size(); ++e) {
    if (!seen[e]) continue;
    const Eigen::Vector3d a = truth.vertices[truth.edges[e].vertex_a];
    const Eigen::Vector3d b = truth.vertices[truth.edges[e].vertex_b];
    const double length = (b - a).norm();
    const int pieces = std::max(1, static_cast<int>(std::ceil(length / options.sample_step_m - 1e-9)));
    const double piece = length / pieces;
    const int k = static_cast<int>(direction[e]);
    figures.seen_length_m += length;
    figures.seen_length_by_direction[k] += length;
    for (int i = 0; i < pieces; ++i) {
      const double t = (i + 0.5) / pieces;
      const Eigen::Vector3d sample = a + t * (b - a);
      bool covered = false;
      for (const auto& [first, second] : edges) {
        if (DistanceToSegment(sample, vertices[first], vertices[second]) <= options.threshold_m) {
          covered = true;
          break;
        }
      }
      if (covered) {
        figures.covered_length_m += piece;
        figures.covered_length_by_direction[k] += piece;
      }
      if (views == nullptr) continue;
      const auto& seen_parts = (*views)[e];
      if (std::none_of(seen_parts.begin(), seen_parts.end(),
                       [t](const std::pair<double, double>& part) { return t >= part.first && t <= part.second; })) {
        continue;
      }
      figures.in_view_length_m += piece;
      if (covered) figures.covered_in_view_length_m += piece;
    }
  }
  figures.completeness = figures.seen_length_m > 0 ? figures.covered_length_m / figures.seen_length_m : nan;

  // Edge precision: samples along the reconstructed edges against every true edge.
  for (const auto& [first, second] : edges) {
    const Eigen::Vector3d a = vertices[first], b = vertices[second];
    const double length = (b - a).norm();
    if (!(length > 0)) continue;
    const int pieces = std::max(1, static_cast<int>(std::ceil(length / options.sample_step_m - 1e-9)));
    const double piece = length / pieces;
    figures.edge_length_m += length;
    for (int i = 0; i < pieces; ++i) {
      const Eigen::Vector3d sample = a + ((i + 0.5) / pieces) * (b - a);
      for (const WireEdge& edge : truth.edges) {
        if (DistanceToSegment(sample, truth.vertices[edge.vertex_a], truth.vertices[edge.vertex_b]) <=
            options.threshold_m) {
          figures.edge_within_m += piece;
          break;
        }
      }
    }
  }
  figures.edge_precision = figures.edge_length_m > 0 ? figures.edge_within_m / figures.edge_length_m : nan;
  return figures;
}

}  // namespace sfm
