#include "backend/triangulation/line_point_agreement.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

namespace sfm {
namespace {

// The (line, point) pairs whose junctions use one detected line segment in every frame that observes
// both (the topology edges' rule, TopologyEdgeOptions::min_support 1): the point's junction is on the
// line's image segment there (its far end, or a junction along it).
std::set<std::pair<int, int>> Candidates(const std::vector<Junctions>& junctions,
                                         const Landmarks& landmarks) {
  const int num_frames = static_cast<int>(junctions.size());
  // Per frame: detected segment -> the drawn points whose junctions use it.
  std::vector<std::map<int, std::vector<std::pair<int, int>>>> users(num_frames);  // (junction, point)
  for (size_t p = 0; p < landmarks.points.size(); ++p) {
    for (const PointObservation& observation : landmarks.points[p].observations) {
      CHECK(observation.frame >= 0 && observation.frame < num_frames) << "frame " << observation.frame;
      const Junctions& frame = junctions[observation.frame];
      CHECK(observation.junction >= 0 && observation.junction < static_cast<int>(frame.size()));
      for (const JunctionSegment& segment : frame[observation.junction].segments) {
        if (segment.line_segment >= 0)
          users[observation.frame][segment.line_segment].emplace_back(observation.junction,
                                                                      static_cast<int>(p));
      }
    }
  }
  std::map<std::pair<int, int>, std::set<int>> joined;  // (line, point) -> the frames showing it
  for (size_t l = 0; l < landmarks.lines.size(); ++l) {
    const LineLandmark& line = landmarks.lines[l];
    for (const LineObservation& observation : line.observations) {
      CHECK(observation.frame >= 0 && observation.frame < num_frames) << "frame " << observation.frame;
      const Junctions& frame = junctions[observation.frame];
      CHECK(observation.junction >= 0 && observation.junction < static_cast<int>(frame.size()));
      const Junction& junction = frame[observation.junction];
      CHECK(observation.segment >= 0 && observation.segment < junction.NumSegments());
      const int detected = junction.segments[observation.segment].line_segment;
      if (detected < 0) continue;
      const auto it = users[observation.frame].find(detected);
      if (it == users[observation.frame].end()) continue;
      for (const auto& [other_junction, point] : it->second) {
        if (other_junction == observation.junction || point == line.point_landmark) continue;
        joined[{static_cast<int>(l), point}].insert(observation.frame);
      }
    }
  }
  std::set<std::pair<int, int>> candidates;
  for (const auto& [pair, frames] : joined) {
    size_t both = 0;
    for (const PointObservation& observation : landmarks.points[pair.second].observations) {
      const std::vector<LineObservation>& seen = landmarks.lines[pair.first].observations;
      both += std::any_of(seen.begin(), seen.end(),
                          [&](const LineObservation& line) { return line.frame == observation.frame; });
    }
    if (frames.size() >= both) candidates.insert(pair);
  }
  return candidates;
}

// A landmark's a-posteriori variance factor, chi2 / dof when above 1 (Foerstner & Wrobel 2016, ch. 4,
// as the wireframe selection's OwnSigmaFactor squared): a landmark whose residuals exceed the pixel
// noise is less certain than its first-order covariance says. 1 without a degree of freedom.
double OwnVarianceFactor(double chi_square, int dof) {
  if (dof < 1 || !std::isfinite(chi_square)) return 1.0;
  return std::max(1.0, chi_square / dof);
}

}  // namespace

void AgreeLinesAndPoints(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                         const std::vector<Junctions>& junctions, const LinePointAgreementOptions& options,
                         Landmarks* landmarks, LinePointAgreementReport* report) {
  CHECK_EQ(world_T_camera.size(), junctions.size());
  CHECK(options.level > 0 && options.level < 1);
  LinePointAgreementReport local;
  std::vector<PointLandmark>& points = landmarks->points;
  std::vector<LineLandmark>& lines = landmarks->lines;
  const std::set<std::pair<int, int>> candidates = Candidates(junctions, *landmarks);
  local.candidates = static_cast<int>(candidates.size());
  const double across_bound2 = ChiSquareQuantile(options.level, 2);  // in units of the variance
  // z sqrt(2) sigma: an observed far end-point's and a junction location's noise along the segment.
  const double along_bound2 = ChiSquareQuantile(options.level, 1);
  const double end_slack_px = std::sqrt(2 * along_bound2) * options.pixel_sigma_px;

  // The points' covariances, computed once (with the poses' drift); false: undetermined.
  std::vector<int> point_state(points.size(), 0);  // 0 not computed, 1 determined, -1 not
  std::vector<Eigen::Matrix3d> point_covariance(points.size());
  auto covariance_of_point = [&](int p) {
    if (point_state[p] == 0) {
      std::vector<Pose3> cameras;
      std::vector<int> frames;
      for (const PointObservation& observation : points[p].observations) {
        cameras.push_back(world_T_camera[observation.frame]);
        frames.push_back(observation.frame);
      }
      point_state[p] = PointPositionCovariance(K, cameras, frames, points[p].position, options.pixel_sigma_px,
                                               options.drift, &point_covariance[p])
                           ? 1
                           : -1;
      std::vector<Eigen::Vector2d> pixels;
      for (const PointObservation& observation : points[p].observations) pixels.push_back(observation.pixel);
      int dof = 0;
      const double chi_square =
          PointChiSquare(K, cameras, pixels, points[p].position, options.pixel_sigma_px, &dof);
      point_covariance[p] *= OwnVarianceFactor(chi_square, dof);
    }
    return point_state[p] > 0;
  };
  auto views_of = [&](const LineLandmark& line) {
    std::vector<LineSegmentView> views;
    for (const LineObservation& observation : line.observations)
      views.push_back({world_T_camera[observation.frame], observation.p0, observation.p1, observation.frame});
    return views;
  };

  struct Fusion {
    int line = -1;
    double ratio = std::numeric_limits<double>::infinity();  // d^T (C_P + C_L)^-1 d across the line
    Eigen::Vector3d target = Eigen::Vector3d::Zero();
  };
  struct Far {
    int point = -1;
    double s = std::numeric_limits<double>::infinity();
    Fusion fusion;
  };
  std::vector<Far> far(lines.size());
  std::vector<Fusion> fusion(points.size());
  std::vector<std::vector<std::pair<double, int>>> interior(lines.size());  // (s, point)
  for (const auto& [l, p] : candidates) {
    const LineLandmark& line = lines[l];
    if (p == line.end1_point) continue;
    const Eigen::Vector3d start = line.point_landmark >= 0 ? points[line.point_landmark].position : line.end0;
    const Eigen::Vector3d along = line.end1 - start;
    const double length = along.norm();
    if (!(length > 0)) continue;
    const Eigen::Vector3d u = along / length;
    const Eigen::Vector3d& x = points[p].position;
    const double s = (x - start).dot(u);
    const Eigen::Vector3d foot = start + s * u;
    if (s <= 0 || !covariance_of_point(p)) continue;
    Eigen::Matrix2d line_covariance;
    Eigen::Matrix<double, 3, 2> plane;  // orthonormal basis across the line
    const std::vector<LineSegmentView> views = views_of(line);
    if (!LinePositionCovariance(K, views, foot, u, options.pixel_sigma_px, options.drift, true,
                                &line_covariance, &plane))
      continue;
    int line_dof = 0;
    line_covariance *= OwnVarianceFactor(
        LineChiSquare(K, views, line.point, line.direction, options.pixel_sigma_px, &line_dof), line_dof);
    // The point's and the line's errors across the line, independent: d ~ N(0, C_P + C_L).
    const Eigen::Matrix2d point_across = plane.transpose() * point_covariance[p] * plane;
    const Eigen::Matrix2d combined = point_across + line_covariance;
    const Eigen::Vector2d d = plane.transpose() * (foot - x);
    const double ratio = d.dot(combined.ldlt().solve(d));
    if (!(ratio <= across_bound2)) continue;
    // The inverse-variance mean of the point and the line across the line (the point's position along
    // the line unchanged): x + C_P (C_P + C_L)^-1 d.
    auto fused = [&]() -> Eigen::Vector3d { return x + plane * (point_across * combined.ldlt().solve(d)); };
    // Where P's projections fall along the observed segments, relative to their far end-points.
    std::vector<double> beyond_px;
    for (const LineObservation& observation : line.observations) {
      const Eigen::Vector3d in_camera = world_T_camera[observation.frame].Inverse() * x;
      const Eigen::Vector2d segment = observation.p1 - observation.p0;
      if (!(in_camera.z() > 0 && segment.norm() > 0)) continue;
      beyond_px.push_back(segment.normalized().dot((K * in_camera).hnormalized() - observation.p1));
    }
    if (beyond_px.empty()) continue;
    std::nth_element(beyond_px.begin(), beyond_px.begin() + beyond_px.size() / 2, beyond_px.end());
    const double beyond = beyond_px[beyond_px.size() / 2];
    if (beyond >= -end_slack_px) {
      // A far end does not shorten the line by more than its end's uncertainty along it
      // (LineEndAlongSigma): a point well inside the line's 3D extent is placed wrong along its rays
      // (the images end the segment at its junction), or is a junction along the line.
      const double end_sigma = LineEndAlongSigma(K, views, line.end1, u, options.pixel_sigma_px,
                                                 std::sqrt(line_covariance.trace()));
      if (line.end1_point < 0 && beyond <= options.max_gap_px + end_slack_px &&
          s >= length - std::sqrt(along_bound2) * end_sigma && s < far[l].s)
        far[l] = {p, s, {static_cast<int>(l), ratio, fused()}};
      continue;
    }
    // Strictly inside: at least the combined sigma from either end.
    const double margin = std::sqrt(combined.trace());
    if (s < margin || s > length - margin) continue;
    interior[l].emplace_back(s, p);
    if (ratio < fusion[p].ratio) fusion[p] = {static_cast<int>(l), ratio, fused()};
  }
  // A far end is fused with its line as a point along it is: the line, measured in every view up to
  // the observed far ends, fixes the position across it better than a point seen from few views.
  for (const Far& end : far) {
    if (end.point >= 0 && end.fusion.ratio < fusion[end.point].ratio) fusion[end.point] = end.fusion;
  }
  for (size_t p = 0; p < points.size(); ++p) {
    if (fusion[p].line < 0) continue;
    points[p].position = fusion[p].target;
    ++local.points_on_lines;
  }
  for (size_t l = 0; l < lines.size(); ++l) {
    LineLandmark& line = lines[l];
    if (far[l].point >= 0) {
      line.end1_point = far[l].point;
      ++local.ends_at_points;
    }
    std::sort(interior[l].begin(), interior[l].end());
    for (const auto& [s, p] : interior[l]) {
      if (p == line.end1_point) continue;
      line.interior_points.push_back(p);
      ++local.splits;
    }
    if (line.end1_point >= 0) line.end1 = points[line.end1_point].position;
  }
  if (report != nullptr) *report = local;
}

}  // namespace sfm
