#include "backend/triangulation/topology_edges.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>

namespace sfm {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// How far along `toward` (a unit vector, `distance` pixels to the other junction) a junction
// segment of `from` covers, taking only segments whose line passes the other junction within the
// 3-sigma bound of TopologyEdgeOptions::pixel_sigma_px. 0 when none does.
double Reach(const Junction& from, const Eigen::Vector2d& toward, double distance, double sigma_px) {
  double reach = 0;
  for (const JunctionSegment& segment : from.segments) {
    const Eigen::Vector2d along = segment.end - from.location;
    const double length = along.norm();
    if (!(length > 0)) continue;
    const double forward = along.dot(toward);
    if (forward <= 0) continue;
    const double offset = std::abs(Cross(along / length, toward)) * distance;
    if (offset > 3 * std::sqrt(2.0) * sigma_px * (1 + distance / length)) continue;
    reach = std::max(reach, std::min(distance, forward));
  }
  return reach;
}

// Whether the image shows junctions a and b joined by one line segment: they use one detected
// segment, or their junction segments point at each other and cover the distance but for the
// end-point model's allowance.
bool Joined(const Junction& a, const Junction& b, const TopologyEdgeOptions& options) {
  for (const JunctionSegment& sa : a.segments) {
    if (sa.line_segment < 0) continue;
    for (const JunctionSegment& sb : b.segments) {
      if (sa.line_segment == sb.line_segment) return true;
    }
  }
  const Eigen::Vector2d u = b.location - a.location;
  const double distance = u.norm();
  if (!(distance > 0)) return false;
  const double reach_a = Reach(a, u / distance, distance, options.pixel_sigma_px);
  const double reach_b = Reach(b, -u / distance, distance, options.pixel_sigma_px);
  return (reach_a > 0 || reach_b > 0) && reach_a + reach_b >= distance - options.max_gap_px;
}

// Whether the frames place the 3D segment ab: the planes through it and the camera centres spread
// by more than the angle whose cosine is min_plane_cos, or, when they do not (the segment lies in
// an epipolar plane), it is within that angle of the baseline from the first to the last frame.
bool Placed(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const std::vector<Pose3>& world_T_camera,
            std::vector<int> frames, double min_plane_cos) {
  std::sort(frames.begin(), frames.end());
  std::vector<Eigen::Vector3d> normals;
  for (const int f : frames) {
    const Eigen::Vector3d& centre = world_T_camera[f].translation;
    const Eigen::Vector3d normal = (a - centre).cross(b - centre);
    if (normal.norm() > 0) normals.push_back(normal.normalized());
  }
  for (size_t i = 0; i < normals.size(); ++i) {
    for (size_t k = i + 1; k < normals.size(); ++k) {
      if (std::abs(normals[i].dot(normals[k])) < min_plane_cos) return true;
    }
  }
  const Eigen::Vector3d baseline =
      world_T_camera[frames.back()].translation - world_T_camera[frames.front()].translation;
  const double lengths = baseline.norm() * (b - a).norm();
  return lengths > 0 && std::abs(baseline.dot(b - a)) >= min_plane_cos * lengths;
}

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace

void AddTopologyEdges(const std::vector<Pose3>& world_T_camera, const std::vector<Junctions>& junctions,
                      const TopologyEdgeOptions& options, Landmarks* landmarks, TopologyEdgeReport* report) {
  CHECK_EQ(world_T_camera.size(), junctions.size());
  CHECK(options.min_support > 0 && options.min_support <= 1);
  CHECK(options.collinear_deg > 0 && options.collinear_deg < 90);
  TopologyEdgeReport local;
  const std::vector<PointLandmark>& points = landmarks->points;
  const int num_frames = static_cast<int>(junctions.size());

  // The drawn point of each (frame, junction), and each point's junction per frame.
  std::vector<std::unordered_map<int, int>> point_of(num_frames);
  std::vector<std::unordered_map<int, int>> junction_of(points.size());
  for (size_t p = 0; p < points.size(); ++p) {
    for (const PointObservation& observation : points[p].observations) {
      CHECK(observation.frame >= 0 && observation.frame < num_frames);
      CHECK(observation.junction >= 0 &&
            observation.junction < static_cast<int>(junctions[observation.frame].size()));
      point_of[observation.frame][observation.junction] = static_cast<int>(p);
      junction_of[p][observation.frame] = observation.junction;
    }
  }

  // Candidates: drawn points whose junctions are consecutive along one detected line segment.
  std::set<std::pair<int, int>> candidates;
  for (int f = 0; f < num_frames; ++f) {
    const Junctions& frame = junctions[f];
    std::map<int, std::vector<int>> users;  // detected segment -> junctions (drawn points) using it
    for (const auto& [junction, point] : point_of[f]) {
      for (const JunctionSegment& segment : frame[junction].segments) {
        if (segment.line_segment < 0) continue;
        std::vector<int>& list = users[segment.line_segment];
        if (std::find(list.begin(), list.end(), junction) == list.end()) list.push_back(junction);
      }
    }
    for (auto& [line, list] : users) {
      if (list.size() < 2) continue;
      std::sort(list.begin(), list.end());  // a fixed order before the geometric one
      const Eigen::Vector2d origin = frame[list.front()].location;
      Eigen::Vector2d direction = Eigen::Vector2d::Zero();
      for (const int j : list) {
        const Eigen::Vector2d d = frame[j].location - origin;
        if (d.squaredNorm() > direction.squaredNorm()) direction = d;
      }
      std::stable_sort(list.begin(), list.end(), [&](int a, int b) {
        return (frame[a].location - origin).dot(direction) < (frame[b].location - origin).dot(direction);
      });
      for (size_t k = 0; k + 1 < list.size(); ++k) {
        const int p = point_of[f].at(list[k]), q = point_of[f].at(list[k + 1]);
        if (p != q) candidates.emplace(std::min(p, q), std::max(p, q));
      }
    }
  }
  local.candidates = static_cast<int>(candidates.size());

  // Each candidate against every frame that observes both of its points.
  const double min_plane_cos = std::cos(options.min_plane_angle_deg * M_PI / 180);
  std::vector<std::pair<int, int>> supported;
  for (const auto& [p, q] : candidates) {
    int joined = 0;
    std::vector<int> both;
    for (const auto& [frame, junction_p] : junction_of[p]) {
      const auto it = junction_of[q].find(frame);
      if (it == junction_of[q].end()) continue;
      both.push_back(frame);
      joined += Joined(junctions[frame][junction_p], junctions[frame][it->second], options);
    }
    if (both.empty() || joined < options.min_support * both.size() - 1e-9) {
      ++local.unsupported;
      continue;
    }
    if (!Placed(points[p].position, points[q].position, world_T_camera, both, min_plane_cos)) {
      ++local.undetermined;
      continue;
    }
    supported.emplace_back(p, q);
  }

  // Split at the drawn points lying on an edge (a T where another line ends on it, or a junction
  // along the line), then remove duplicates.
  const double tolerance = std::tan(options.collinear_deg * M_PI / 180);
  std::set<std::pair<int, int>> edges;
  for (const auto& [p, q] : supported) {
    const Eigen::Vector3d a = points[p].position, b = points[q].position;
    const Eigen::Vector3d ab = b - a;
    const double length2 = ab.squaredNorm();
    if (!(length2 > 0)) continue;
    std::vector<std::pair<double, int>> chain = {{0.0, p}, {1.0, q}};
    for (size_t r = 0; r < points.size(); ++r) {
      if (static_cast<int>(r) == p || static_cast<int>(r) == q) continue;
      const Eigen::Vector3d x = points[r].position;
      const double t = (x - a).dot(ab) / length2;
      if (t <= 0 || t >= 1) continue;
      const double off = (x - (a + t * ab)).norm();
      if (off <= tolerance * std::min((x - a).norm(), (x - b).norm()))
        chain.emplace_back(t, static_cast<int>(r));
    }
    std::sort(chain.begin(), chain.end());
    local.splits += static_cast<int>(chain.size()) - 2;
    for (size_t k = 0; k + 1 < chain.size(); ++k) {
      const int u = chain[k].second, v = chain[k + 1].second;
      edges.emplace(std::min(u, v), std::max(u, v));
    }
  }
  landmarks->point_edges.assign(edges.begin(), edges.end());
  local.edges = static_cast<int>(edges.size());

  // Line landmarks lying on an edge (before its splits) duplicate it: the edge ends at measured
  // points, the line at an extrapolated far end.
  std::vector<LineLandmark> lines;
  lines.reserve(landmarks->lines.size());
  for (LineLandmark& line : landmarks->lines) {
    bool on_edge = false;
    for (const auto& [p, q] : supported) {
      const Eigen::Vector3d a = points[p].position, b = points[q].position;
      const double bound = tolerance * (b - a).norm();
      if (DistanceToSegment(line.end0, a, b) <= bound && DistanceToSegment(line.end1, a, b) <= bound) {
        on_edge = true;
        break;
      }
    }
    if (on_edge) {
      ++local.lines_dropped;
    } else {
      lines.push_back(std::move(line));
    }
  }
  landmarks->lines = std::move(lines);
  if (report) *report = local;
}

}  // namespace sfm
