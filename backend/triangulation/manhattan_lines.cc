#include "backend/triangulation/manhattan_lines.h"

#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "backend/triangulation/line_triangulation.h"
#include "backend/triangulation/wireframe_selection.h"

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Item {
  Eigen::Vector3d direction;  // unit
  double weight;              // length
};

// The direction with the most weight within cos_inlier of it among `items` (each item's own
// direction tried; signs ignored), refined as the principal eigenvector of its inliers' weighted
// outer products. False when no item is given.
bool StrongestDirection(const std::vector<Item>& items, double cos_inlier, Eigen::Vector3d* direction) {
  double best = 0;
  int best_item = -1;
  for (size_t i = 0; i < items.size(); ++i) {
    double weight = 0;
    for (const Item& other : items) {
      if (std::abs(items[i].direction.dot(other.direction)) >= cos_inlier) weight += other.weight;
    }
    if (weight > best) {
      best = weight;
      best_item = static_cast<int>(i);
    }
  }
  if (best_item < 0) return false;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Item& other : items) {
    if (std::abs(items[best_item].direction.dot(other.direction)) >= cos_inlier)
      scatter += other.weight * other.direction * other.direction.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  *direction = solver.eigenvectors().col(2);
  return true;
}

// A junction segment that may end where a nearer edge hides it (the stem of a T, either bar of an
// X): its line need not pass through the junction's 3D point, which lies on the nearer edge.
// A T's bar is the two segments of one detected line segment.
bool MayBeOccluded(const Junction& junction, int segment) {
  if (junction.type == JunctionType::kX) return true;
  if (junction.type != JunctionType::kT) return false;
  const int detected = junction.segments[segment].line_segment;
  for (int other = 0; other < junction.NumSegments(); ++other) {
    if (other != segment && detected >= 0 && junction.segments[other].line_segment == detected) return false;
  }
  return true;
}

}  // namespace

DominantDirections EstimateDominantDirections(const Landmarks& drawn, double inlier_deg) {
  CHECK(inlier_deg > 0 && inlier_deg < 45) << inlier_deg;
  std::vector<Item> items;
  auto add = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const double length = (b - a).norm();
    if (length > 0 && std::isfinite(length)) items.push_back({(b - a) / length, length});
  };
  for (const LineLandmark& line : drawn.lines) add(line.end0, line.end1);
  for (const auto& [a, b] : drawn.point_edges) add(drawn.points[a].position, drawn.points[b].position);
  DominantDirections result;
  const double cos_inlier = std::cos(inlier_deg * kPi / 180);
  const double sin_inlier = std::sin(inlier_deg * kPi / 180);
  Eigen::Vector3d first, second;
  if (!StrongestDirection(items, cos_inlier, &first)) return result;
  std::vector<Item> perpendicular;
  for (const Item& item : items) {
    if (std::abs(item.direction.dot(first)) <= sin_inlier) perpendicular.push_back(item);
  }
  if (!StrongestDirection(perpendicular, cos_inlier, &second)) return result;
  second = (second - second.dot(first) * first).normalized();
  result.axes.col(0) = first;
  result.axes.col(1) = second;
  result.axes.col(2) = first.cross(second);
  result.found = true;
  double total = 0, inlier = 0, squared_angle = 0;
  for (const Item& item : items) {
    total += item.weight;
    const double best = (result.axes.transpose() * item.direction).cwiseAbs().maxCoeff();
    if (best < cos_inlier) continue;
    inlier += item.weight;
    const double angle = std::acos(std::min(1.0, best));
    squared_angle += item.weight * angle * angle;
  }
  result.support = total > 0 ? inlier / total : 0;
  result.sigma_rad = inlier > 0 ? std::sqrt(squared_angle / inlier) : 0;
  return result;
}

void PlaceManhattanLines(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                         const std::vector<Junctions>& junctions, const std::vector<JunctionTrack>& tracks,
                         const ManhattanLineOptions& options, Landmarks* drawn, ManhattanLineReport* report) {
  CHECK_EQ(world_T_camera.size(), junctions.size());
  CHECK(options.level > 0 && options.level < 1);
  CHECK(options.min_support > 0 && options.min_support <= 1) << options.min_support;
  CHECK_GE(options.min_views, 2);
  CHECK_GT(options.max_end_spread_px, 0);
  ManhattanLineReport local;
  local.directions = EstimateDominantDirections(*drawn, options.inlier_deg);
  const DominantDirections& directions = local.directions;
  if (!directions.found || directions.support < options.min_support) {
    if (report != nullptr) *report = local;
    return;
  }
  std::unordered_map<int, int> track_of_id;
  for (size_t t = 0; t < tracks.size(); ++t) track_of_id[tracks[t].id] = static_cast<int>(t);
  std::set<std::tuple<int, int, int>> used;  // (frame, junction, segment) of the drawn lines
  for (const LineLandmark& line : drawn->lines) {
    for (const LineObservation& observation : line.observations)
      used.insert({observation.frame, observation.junction, observation.segment});
  }
  WireframeOptions bound = options.wireframe;
  bound.pixel_sigma_px = options.pixel_sigma_px;
  const int num_frames = static_cast<int>(junctions.size());
  const size_t num_points = drawn->points.size();
  for (size_t p = 0; p < num_points; ++p) {
    const PointLandmark& point = drawn->points[p];
    const auto found = track_of_id.find(point.track_id);
    if (found == track_of_id.end() || point.occlusion_candidate) continue;
    const JunctionTrack& track = tracks[found->second];
    const Eigen::Vector3d P = point.position;
    double point_sigma = -1;  // computed once, on the first candidate
    for (int s = 0; s < track.NumSegments(); ++s) {
      std::vector<LineObservation> observations;
      std::vector<LineView> views;
      std::vector<LineSegmentView> segment_views;
      std::vector<Eigen::Vector4d> planes;
      bool taken = false;
      for (const TrackView& view : track.views) {
        if (view.segments[s] < 0) continue;
        CHECK(view.frame >= 0 && view.frame < num_frames) << "frame " << view.frame;
        const Junctions& frame = junctions[view.frame];
        CHECK(view.junction >= 0 && view.junction < static_cast<int>(frame.size()));
        const Junction& junction = frame[view.junction];
        CHECK(view.segments[s] < junction.NumSegments());
        const Eigen::Vector2d p1 = junction.segments[view.segments[s]].end;
        if (!((p1 - junction.location).norm() > 0)) continue;
        taken = taken || used.count({view.frame, view.junction, view.segments[s]}) > 0 ||
                MayBeOccluded(junction, view.segments[s]);
        const Pose3& pose = world_T_camera[view.frame];
        observations.push_back({view.frame, view.junction, view.segments[s], junction.location, p1});
        views.push_back({pose, junction.location, p1});
        segment_views.push_back({pose, junction.location, p1, view.frame});
        planes.push_back(BackProjectedPlane(K, views.back()));
      }
      if (taken || static_cast<int>(views.size()) < options.min_views ||
          MaxPlaneAngle(planes) > options.min_plane_angle_deg * kPi / 180)
        continue;
      ++local.candidates;
      // The image test of each dominant direction through P (H&Z 8.1.2: each view's segment must lie
      // on the line's image).
      const int n = static_cast<int>(views.size());
      const double bound2 = ChiSquareQuantile(options.level, 2 * n - 2);
      int passing = 0;
      Eigen::Vector3d direction = Eigen::Vector3d::Zero();
      for (int a = 0; a < 3; ++a) {
        int dof = 0;
        const double chi_square =
            LineChiSquare(K, segment_views, P, directions.axes.col(a), options.pixel_sigma_px, &dof);
        if (chi_square <= bound2) {
          ++passing;
          direction = directions.axes.col(a);
        }
      }
      if (passing == 0) {
        ++local.inconsistent;
        continue;
      }
      if (passing > 1) {
        ++local.ambiguous;
        continue;
      }
      // A far end-point at the image border may be where the edge leaves the view, not where it
      // ends: it bounds the edge's extent from below and says nothing of its end.
      std::vector<bool> clipped(views.size(), false);
      int num_clipped = 0;
      for (size_t i = 0; i < views.size(); ++i) {
        const Eigen::Vector2d beyond =
            views[i].p1 + options.border_step_px * (views[i].p1 - views[i].p0).normalized();
        clipped[i] = options.seen_by_image && !options.seen_by_image(beyond);
        num_clipped += clipped[i];
      }
      Segment3 segment;
      std::vector<LineSegmentView> seeing_end;  // the views that see end1
      if (n - num_clipped >= 2) {
        // Enough views end the edge in the image: they must agree on one end (clipped views
        // left out).
        std::vector<LineView> ended;
        std::vector<LineSegmentView> ended_segments;
        for (int i = 0; i < n; ++i) {
          if (clipped[i]) continue;
          ended.push_back(views[i]);
          ended_segments.push_back(segment_views[i]);
        }
        if (BoundLine(K, ended, Line3{P, direction}, &P, options.line, &segment) != LineStatus::kOk) {
          ++local.unbounded;
          continue;
        }
        // Within the plane the images hold only the far end-points' positions along the segments:
        // a line in the plane but off the chosen direction, or an end that moves (occluded), shows
        // as far end-points spread along the segments about end1's projections.
        double spread_px = 0;
        for (const LineView& view : ended) {
          const Eigen::Vector2d end = (K * (view.world_T_camera.Inverse() * segment.end1)).hnormalized();
          spread_px = std::max(spread_px, std::abs((view.p1 - view.p0).normalized().dot(view.p1 - end)));
        }
        if (!(spread_px <= options.max_end_spread_px)) {
          ++local.ends_disagree;
          continue;
        }
        seeing_end = std::move(ended_segments);
      } else {
        // The edge leaves the view in (nearly) every view: it reaches at least as far as the
        // second-farthest far end-point, the extent two views see.
        const Line3 line{P, direction};
        std::vector<std::optional<double>> far_of_view;
        std::vector<double> far;
        double sum = 0;
        for (const LineView& view : views) {
          far_of_view.push_back(BackProjectOntoLine(K, view.world_T_camera, view.p1, line));
          if (!far_of_view.back()) continue;
          far.push_back(*far_of_view.back());
          sum += far.back();
        }
        if (far.size() < 2) {
          ++local.unbounded;
          continue;
        }
        const double sign = sum >= 0 ? 1 : -1;
        for (double& s_far : far) s_far *= sign;
        std::nth_element(far.begin(), far.begin() + 1, far.end(), std::greater<double>());
        const double extent = far[1];
        if (!(extent > 0)) {
          ++local.unbounded;
          continue;
        }
        segment = {P, P + sign * extent * direction};
        bool too_close = false;
        for (int i = 0; i < n; ++i) {
          if (!far_of_view[i] || sign * *far_of_view[i] < extent) continue;
          seeing_end.push_back(segment_views[i]);
          const double depth = (views[i].world_T_camera.Inverse() * segment.end1).z();
          too_close = too_close || !(depth >= options.line.min_depth_m);
        }
        if (too_close) {
          ++local.unbounded;
          continue;
        }
      }
      const double length = (segment.end1 - segment.end0).norm();
      const Eigen::Vector3d u = (segment.end1 - segment.end0) / length;
      if (point_sigma < 0) {
        std::vector<Pose3> cameras;
        std::vector<int> frames;
        for (const PointObservation& observation : point.observations) {
          cameras.push_back(world_T_camera[observation.frame]);
          frames.push_back(observation.frame);
        }
        point_sigma = PointPositionSigma(K, cameras, frames, P, options.pixel_sigma_px, options.drift);
      }
      const double across = std::hypot(point_sigma, length * directions.sigma_rad);
      const double along =
          LineEndAlongSigma(K, seeing_end, segment.end1, u, options.pixel_sigma_px, across);
      double depth = std::numeric_limits<double>::infinity();
      for (const LineSegmentView& view : seeing_end)
        depth = std::min(depth, (view.world_T_camera.Inverse() * segment.end1).z());
      if (!(std::hypot(across, along) <= MaxVertexSigma(bound, K(0, 0), depth))) {
        ++local.undetermined;
        continue;
      }
      LineLandmark line;
      line.point = P;
      line.direction = u;
      line.end0 = P;
      line.end1 = segment.end1;
      line.point_landmark = static_cast<int>(p);
      line.observations = observations;
      drawn->lines.push_back(line);
      for (const LineObservation& observation : observations)
        used.insert({observation.frame, observation.junction, observation.segment});
      ++local.placed;
      if (n - num_clipped < 2) ++local.leaving_view;
    }
  }
  if (report != nullptr) *report = local;
}

}  // namespace sfm
