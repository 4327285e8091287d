#include "backend/triangulation/track_extension.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <string>

#include <Eigen/Dense>

#include "backend/triangulation/landmark_uncertainty.h"
#include "frontend/junctions/location_information.h"

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A landmark point seen from one camera: pixel, depth and the 2x3 derivative of the pixel by the
// world point (the pinhole projection, H&Z section 6.1).
struct Projection {
  Eigen::Vector2d pixel;
  double depth = 0;
  Eigen::Matrix<double, 2, 3> jacobian;
};

Projection Project(const Eigen::Matrix3d& K, const Pose3& world_T_camera, const Eigen::Vector3d& world) {
  const Eigen::Matrix3d R = world_T_camera.RotationMatrix().transpose();  // camera_R_world
  const Eigen::Vector3d c = R * (world - world_T_camera.translation);
  Projection p;
  p.depth = c.z();
  const double fx = K(0, 0), fy = K(1, 1);
  p.pixel = {fx * c.x() / c.z() + K(0, 2), fy * c.y() / c.z() + K(1, 2)};
  Eigen::Matrix<double, 2, 3> d;
  d << fx / c.z(), 0, -fx * c.x() / (c.z() * c.z()), 0, fy / c.z(), -fy * c.y() / (c.z() * c.z());
  p.jacobian = d * R;
  return p;
}

// Where each segment track of a track should point in a frame (image unit vector), or nothing.
using Directions = std::vector<std::optional<Eigen::Vector2d>>;

// The junction's segments assigned to the track's segment tracks: assign[k] = s for junction
// segment k. Every junction segment must be within max_angle of exactly one predicted direction
// (distinct ones), and every segment track with a 3D line (`required`) must get one.
std::optional<std::vector<int>> AssignSegments(const Junction& junction, const Directions& predicted,
                                               const std::vector<bool>& required, double max_angle_rad) {
  const int m = junction.NumSegments();
  std::vector<int> assign(m, -1);
  std::vector<bool> used(predicted.size(), false);
  const double min_cos = std::cos(max_angle_rad);
  for (int k = 0; k < m; ++k) {
    const Eigen::Vector2d d = junction.SegmentDirection(k);
    for (size_t s = 0; s < predicted.size(); ++s) {
      if (!predicted[s] || d.dot(*predicted[s]) < min_cos) continue;
      if (assign[k] >= 0) return std::nullopt;  // two segment tracks fit one segment: ambiguous
      assign[k] = static_cast<int>(s);
    }
    if (assign[k] < 0 || used[assign[k]]) return std::nullopt;
    used[assign[k]] = true;
  }
  for (size_t s = 0; s < predicted.size(); ++s) {
    if (required[s] && !used[s]) return std::nullopt;
  }
  return assign;
}

class Extender {
 public:
  Extender(const Eigen::Matrix3d& K, const Eigen::Vector2d& seen_min, const Eigen::Vector2d& seen_max,
           const std::vector<Pose3>& poses, const std::vector<Junctions>& junctions,
           const TrackExtensionOptions& options, std::vector<JunctionTrack>* tracks, Landmarks* landmarks,
           TrackExtensionReport* report)
      : K_(K),
        seen_min_(seen_min),
        seen_max_(seen_max),
        poses_(poses),
        junctions_(junctions),
        options_(options),
        tracks_(*tracks),
        landmarks_(*landmarks),
        report_(*report) {}

  void Run() {
    Index();
    // Long tracks first: their landmarks are the best determined, and a merge then keeps them.
    std::vector<int> order(landmarks_.points.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return landmarks_.points[a].observations.size() > landmarks_.points[b].observations.size();
    });
    for (int p : order) {
      if (!point_removed_[p]) ExtendPoint(p);
    }
    Finish();
  }

 private:
  // Owners of every junction, each track's point and its lines by segment track.
  void Index() {
    const int n = static_cast<int>(tracks_.size());
    owner_.resize(junctions_.size());
    for (size_t f = 0; f < junctions_.size(); ++f) owner_[f].assign(junctions_[f].size(), -1);
    for (int t = 0; t < n; ++t) {
      CHECK_EQ(tracks_[t].id, t) << "tracks must be numbered 0..n-1 in order";
      for (const TrackView& view : tracks_[t].views) owner_[view.frame][view.junction] = t;
    }
    point_of_track_.assign(n, -1);
    for (size_t p = 0; p < landmarks_.points.size(); ++p) point_of_track_[landmarks_.points[p].track_id] = p;
    line_of_.assign(n, {});
    for (int t = 0; t < n; ++t) line_of_[t].assign(tracks_[t].NumSegments(), -1);
    for (size_t l = 0; l < landmarks_.lines.size(); ++l) {
      const LineObservation& o = landmarks_.lines[l].observations.front();
      const int t = owner_[o.frame][o.junction];
      CHECK_GE(t, 0) << "a line observation outside every track";
      for (const TrackView& view : tracks_[t].views) {
        if (view.frame != o.frame) continue;
        for (size_t s = 0; s < view.segments.size(); ++s) {
          if (view.segments[s] == o.segment) line_of_[t][s] = static_cast<int>(l);
        }
      }
    }
    point_removed_.assign(landmarks_.points.size(), false);
    line_removed_.assign(landmarks_.lines.size(), false);
    point_changed_.assign(landmarks_.points.size(), false);
    line_changed_.assign(landmarks_.lines.size(), false);
    track_alive_.assign(n, true);
  }

  // First-order covariance of a point from its observations: sigma^2 (sum J^T J)^-1 (H&Z A6).
  std::optional<Eigen::Matrix3d> PointCovariance(const PointLandmark& point) const {
    Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
    for (const PointObservation& o : point.observations) {
      const Projection p = Project(K_, poses_[o.frame], point.position);
      if (p.depth <= 0) return std::nullopt;
      information += p.jacobian.transpose() * p.jacobian;
    }
    Eigen::FullPivLU<Eigen::Matrix3d> lu(information);
    if (!lu.isInvertible()) return std::nullopt;
    return Eigen::Matrix3d(options_.pixel_sigma_px * options_.pixel_sigma_px * lu.inverse());
  }

  // The predicted direction of each segment track in frame f, and which are required (have a line).
  void PredictDirections(int t, int f, const Eigen::Vector2d& pixel, Directions* predicted,
                         std::vector<bool>* required) const {
    const JunctionTrack& track = tracks_[t];
    predicted->assign(track.NumSegments(), std::nullopt);
    required->assign(track.NumSegments(), false);
    for (int s = 0; s < track.NumSegments(); ++s) {
      const int l = line_of_[t][s];
      if (l >= 0 && !line_removed_[l]) {
        const LineLandmark& line = landmarks_.lines[l];
        // A point 10 cm along the line from the junction: its image direction from the junction.
        const Eigen::Vector3d step = line.end0 + 0.1 * (line.end1 - line.end0).normalized();
        const Projection q = Project(K_, poses_[f], step);
        if (q.depth > options_.min_depth_m && (q.pixel - pixel).norm() > 1e-6) {
          (*predicted)[s] = (q.pixel - pixel).normalized();
          (*required)[s] = true;
          continue;
        }
      }
      // No 3D line: the segment as the track's nearest view saw it.
      int best = -1;
      for (size_t v = 0; v < track.views.size(); ++v) {
        if (track.views[v].segments[s] < 0) continue;
        if (best < 0 || std::abs(track.views[v].frame - f) < std::abs(track.views[best].frame - f)) best = v;
      }
      if (best >= 0) {
        const TrackView& view = track.views[best];
        (*predicted)[s] = junctions_[view.frame][view.junction].SegmentDirection(view.segments[s]);
      }
    }
  }

  bool TrackHasFrame(int t, int f) const {
    for (const TrackView& view : tracks_[t].views) {
      if (view.frame == f) return true;
    }
    return false;
  }

  // What a search of frame f for track t's point found.
  enum class Search { kOutside, kTooWide, kEmpty, kIncompatible, kAmbiguous, kFound };

  // The one junction of frame f inside the gate of track t's point X (covariance `covariance`)
  // whose segments fit the track's predicted directions: its index and segment assignment.
  Search FindJunction(int t, const Eigen::Vector3d& X, const Eigen::Matrix3d& covariance, int f, int* found,
                      std::vector<int>* found_assign) const {
    const double gate = -2 * std::log(1 - options_.gate_probability);  // chi-square, 2 dof
    const double fx_step = K_(0, 0) * options_.rotation_step_rad;
    const double max_angle = options_.max_angle_deg * kPi / 180;
    const Projection proj = Project(K_, poses_[f], X);
    if (proj.depth < options_.min_depth_m) return Search::kOutside;
    if (proj.pixel.x() < seen_min_.x() || proj.pixel.y() < seen_min_.y() || proj.pixel.x() > seen_max_.x() ||
        proj.pixel.y() > seen_max_.y()) {
      return Search::kOutside;
    }
    int gap = static_cast<int>(poses_.size());
    for (const TrackView& view : tracks_[t].views) gap = std::min(gap, std::abs(view.frame - f));
    const Eigen::Matrix2d S = proj.jacobian * covariance * proj.jacobian.transpose() +
                              (options_.pixel_sigma_px * options_.pixel_sigma_px + fx_step * fx_step * gap) *
                                  Eigen::Matrix2d::Identity();
    // The gate's largest radius: a projection too uncertain to tell crowded junctions apart.
    const double radius = std::sqrt(gate * Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(S).eigenvalues()(1));
    if (radius > options_.max_gate_px) return Search::kTooWide;
    const Eigen::Matrix2d S_inv = S.inverse();
    Directions predicted;
    std::vector<bool> required;
    PredictDirections(t, f, proj.pixel, &predicted, &required);
    int compatible = 0, inside = 0;
    const Junctions& frame = junctions_[f];
    for (size_t j = 0; j < frame.size(); ++j) {
      const Eigen::Vector2d r = frame[j].location - proj.pixel;
      if (std::abs(r.x()) > radius || std::abs(r.y()) > radius || r.dot(S_inv * r) > gate) continue;
      ++inside;
      std::optional<std::vector<int>> assign = AssignSegments(frame[j], predicted, required, max_angle);
      if (!assign) continue;
      ++compatible;
      *found = static_cast<int>(j);
      *found_assign = *assign;
    }
    if (inside == 0) return Search::kEmpty;
    if (compatible == 0) return Search::kIncompatible;
    return compatible > 1 ? Search::kAmbiguous : Search::kFound;
  }

  void ExtendPoint(int p) {
    const std::optional<Eigen::Matrix3d> covariance = PointCovariance(landmarks_.points[p]);
    if (!covariance) return;
    const int t = landmarks_.points[p].track_id;
    const Eigen::Vector3d X = landmarks_.points[p].position;
    for (int f = 0; f < static_cast<int>(poses_.size()); ++f) {
      if (TrackHasFrame(t, f)) continue;
      int found = -1;
      std::vector<int> found_assign;
      const Search search = FindJunction(t, X, *covariance, f, &found, &found_assign);
      if (search == Search::kTooWide) ++report_.gate_too_wide;
      if (search == Search::kEmpty) ++report_.no_junction;
      if (search == Search::kIncompatible) ++report_.incompatible;
      if (search == Search::kAmbiguous) ++report_.ambiguous;
      if (search != Search::kFound) continue;
      const int owner = owner_[f][found];
      if (owner < 0) {
        AddView(t, p, f, found, found_assign);
      } else if (owner != t) {
        if (!Merge(t, p, *covariance, owner, f, found, found_assign)) ++report_.merges_refused;
      }
    }
  }

  // An unassigned junction joins track t, its point p and its lines.
  void AddView(int t, int p, int f, int j, const std::vector<int>& assign) {
    const Junction& junction = junctions_[f][j];
    TrackView view;
    view.frame = f;
    view.junction = j;
    view.segments.assign(tracks_[t].NumSegments(), -1);
    for (size_t k = 0; k < assign.size(); ++k) view.segments[assign[k]] = static_cast<int>(k);
    tracks_[t].views.push_back(view);
    owner_[f][j] = t;
    landmarks_.points[p].observations.push_back({f, j, junction.location, LocationSqrtInformation(junction)});
    point_changed_[p] = true;
    for (size_t k = 0; k < assign.size(); ++k) {
      const int l = line_of_[t][assign[k]];
      if (l < 0 || line_removed_[l]) continue;
      landmarks_.lines[l].observations.push_back({f, j, static_cast<int>(k), junction.location,
                                                  junction.segments[k].end});
      line_changed_[l] = true;
    }
    ++report_.observations_added;
  }

  // Track t2 (which holds junction j of frame f) into track t, when they share no frame and t2's
  // point agrees with t's within their uncertainty (chi-square, 3 dof, at the gate's probability).
  bool Merge(int t, int p, const Eigen::Matrix3d& covariance, int t2, int f, int j, const std::vector<int>& assign) {
    for (const TrackView& v2 : tracks_[t2].views) {
      if (TrackHasFrame(t, v2.frame)) {
        ++report_.merge_overlap;
        return false;
      }
    }
    const int p2 = point_of_track_[t2];
    // Track t's point must explain every view of t2: in each of t2's frames the one compatible
    // junction inside its gate is t2's junction there. (A single frame's unique candidate can be a
    // crowded neighbour; a track without a point has no other test.)
    for (const TrackView& v2 : tracks_[t2].views) {
      int found = -1;
      std::vector<int> found_assign;
      if (FindJunction(t, landmarks_.points[p].position, covariance, v2.frame, &found, &found_assign) !=
              Search::kFound ||
          found != v2.junction) {
        ++report_.merge_unexplained;
        return false;
      }
    }
    if (p2 >= 0) {
      const std::optional<Eigen::Matrix3d> covariance2 = PointCovariance(landmarks_.points[p2]);
      if (!covariance2) return false;
      const Eigen::Vector3d d = landmarks_.points[p].position - landmarks_.points[p2].position;
      const double chi2 = d.dot((covariance + *covariance2).inverse() * d);
      if (!(chi2 <= ChiSquareQuantile(options_.gate_probability, 3))) {
        ++report_.merge_disagree;
        return false;
      }
    }
    // t2's segment tracks in t's numbering: through junction j, whose segment k is t's assign[k].
    const TrackView* at_f = nullptr;
    for (const TrackView& v2 : tracks_[t2].views) {
      if (v2.frame == f) at_f = &v2;
    }
    CHECK(at_f != nullptr && at_f->junction == j);
    const int n2 = tracks_[t2].NumSegments();
    std::vector<int> to_t(n2, -1);
    for (int s2 = 0; s2 < n2; ++s2) {
      if (at_f->segments[s2] >= 0) to_t[s2] = assign[at_f->segments[s2]];
    }
    for (int s2 = 0; s2 < n2; ++s2) {
      if (to_t[s2] >= 0) continue;
      to_t[s2] = tracks_[t].NumSegments();  // a segment track t did not have
      for (TrackView& view : tracks_[t].views) view.segments.push_back(-1);
      line_of_[t].push_back(-1);
    }
    const std::vector<TrackView> old_views = tracks_[t].views;
    for (const TrackView& v2 : tracks_[t2].views) {
      TrackView view;
      view.frame = v2.frame;
      view.junction = v2.junction;
      view.segments.assign(tracks_[t].NumSegments(), -1);
      for (int s2 = 0; s2 < n2; ++s2) view.segments[to_t[s2]] = v2.segments[s2];
      tracks_[t].views.push_back(view);
      owner_[v2.frame][v2.junction] = t;
    }
    // The point: t2's vetted observations, or t2's views when it had no point.
    PointLandmark& point = landmarks_.points[p];
    if (p2 >= 0) {
      for (const PointObservation& o : landmarks_.points[p2].observations) point.observations.push_back(o);
      point_removed_[p2] = true;
    } else {
      for (const TrackView& v2 : tracks_[t2].views) {
        const Junction& junction = junctions_[v2.frame][v2.junction];
        point.observations.push_back(
            {v2.frame, v2.junction, junction.location, LocationSqrtInformation(junction)});
      }
    }
    point_changed_[p] = true;
    // The lines, segment track by segment track.
    for (int s2 = 0; s2 < n2; ++s2) {
      const int s = to_t[s2];
      const int l2 = line_of_[t2][s2] >= 0 && !line_removed_[line_of_[t2][s2]] ? line_of_[t2][s2] : -1;
      const int l = line_of_[t][s] >= 0 && !line_removed_[line_of_[t][s]] ? line_of_[t][s] : -1;
      if (l >= 0 && l2 >= 0) {
        for (const LineObservation& o : landmarks_.lines[l2].observations) landmarks_.lines[l].observations.push_back(o);
        line_removed_[l2] = true;
        line_changed_[l] = true;
      } else if (l >= 0) {
        AppendLineViews(tracks_[t2].views, s2, &landmarks_.lines[l]);
        line_changed_[l] = true;
      } else if (l2 >= 0) {
        // t2's line becomes t's, at t's point; t's own views of it join.
        line_of_[t][s] = l2;
        landmarks_.lines[l2].point_landmark = p;
        AppendLineViews(old_views, s, &landmarks_.lines[l2]);
        line_changed_[l2] = true;
      }
    }
    track_alive_[t2] = false;
    tracks_[t2].views.clear();
    ++report_.tracks_merged;
    return true;
  }

  // The views' segment s as observations of `line`.
  void AppendLineViews(const std::vector<TrackView>& views, int s, LineLandmark* line) const {
    for (const TrackView& view : views) {
      const int k = view.segments[s];
      if (k < 0) continue;
      const Junction& junction = junctions_[view.frame][view.junction];
      line->observations.push_back({view.frame, view.junction, k, junction.location, junction.segments[k].end});
    }
  }

  // Drops the merged landmarks and tracks, sorts, renumbers.
  void Finish() {
    auto by_frame = [](const auto& a, const auto& b) { return a.frame < b.frame; };
    std::vector<int> new_point(landmarks_.points.size(), -1);
    std::vector<PointLandmark> points;
    for (size_t p = 0; p < landmarks_.points.size(); ++p) {
      if (point_removed_[p]) continue;
      new_point[p] = static_cast<int>(points.size());
      points.push_back(std::move(landmarks_.points[p]));
      std::sort(points.back().observations.begin(), points.back().observations.end(), by_frame);
      if (point_changed_[p]) {
        report_.changed_points.push_back(new_point[p]);
        for (const PointObservation& o : points.back().observations) {
          const JunctionType type = junctions_[o.frame][o.junction].type;
          if (type == JunctionType::kT || type == JunctionType::kX) points.back().occlusion_candidate = true;
        }
      }
    }
    std::vector<LineLandmark> lines;
    for (size_t l = 0; l < landmarks_.lines.size(); ++l) {
      if (line_removed_[l]) continue;
      LineLandmark line = std::move(landmarks_.lines[l]);
      std::sort(line.observations.begin(), line.observations.end(), by_frame);
      if (line.point_landmark >= 0) line.point_landmark = new_point[line.point_landmark];
      const bool point_changed =
          line.point_landmark >= 0 && std::binary_search(report_.changed_points.begin(),
                                                         report_.changed_points.end(), line.point_landmark);
      if (line_changed_[l] || point_changed) report_.changed_lines.push_back(static_cast<int>(lines.size()));
      lines.push_back(std::move(line));
    }
    landmarks_.points = std::move(points);
    landmarks_.lines = std::move(lines);

    std::vector<JunctionTrack> tracks;
    std::vector<int> new_track(tracks_.size(), -1);
    for (size_t t = 0; t < tracks_.size(); ++t) {
      if (!track_alive_[t]) continue;
      std::sort(tracks_[t].views.begin(), tracks_[t].views.end(), by_frame);
      tracks.push_back(std::move(tracks_[t]));
    }
    std::vector<int> order(tracks.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const TrackView &va = tracks[a].views.front(), &vb = tracks[b].views.front();
      return std::make_pair(va.frame, va.junction) < std::make_pair(vb.frame, vb.junction);
    });
    std::map<int, int> id_of;  // old id -> new id
    std::vector<JunctionTrack> sorted;
    for (int i : order) {
      id_of[tracks[i].id] = static_cast<int>(sorted.size());
      tracks[i].id = static_cast<int>(sorted.size());
      sorted.push_back(std::move(tracks[i]));
    }
    for (PointLandmark& point : landmarks_.points) point.track_id = id_of.at(point.track_id);
    tracks_ = std::move(sorted);
  }

  const Eigen::Matrix3d K_;
  const Eigen::Vector2d seen_min_, seen_max_;
  const std::vector<Pose3>& poses_;
  const std::vector<Junctions>& junctions_;
  const TrackExtensionOptions& options_;
  std::vector<JunctionTrack>& tracks_;
  Landmarks& landmarks_;
  TrackExtensionReport& report_;

  std::vector<std::vector<int>> owner_;  // [frame][junction] -> track or -1
  std::vector<int> point_of_track_;
  std::vector<std::vector<int>> line_of_;  // [track][segment track] -> line or -1
  std::vector<bool> point_removed_, line_removed_, point_changed_, line_changed_, track_alive_;
};

}  // namespace

Status TrackExtensionOptions::Check() const {
  auto bad = [](const std::string& what) { return Status::Error("TrackExtensionOptions: " + what); };
  if (!(pixel_sigma_px > 0 && std::isfinite(pixel_sigma_px))) return bad("pixel_sigma_px must be finite and > 0");
  if (!(rotation_step_rad >= 0 && std::isfinite(rotation_step_rad))) {
    return bad("rotation_step_rad must be finite and >= 0");
  }
  if (!(gate_probability > 0 && gate_probability < 1)) return bad("gate_probability must be in (0, 1)");
  if (!(max_gate_px > 0 && std::isfinite(max_gate_px))) return bad("max_gate_px must be finite and > 0");
  if (!(max_angle_deg > 0 && max_angle_deg < 90)) return bad("max_angle_deg must be in (0, 90)");
  if (!(min_depth_m >= 0 && std::isfinite(min_depth_m))) return bad("min_depth_m must be finite and >= 0");
  return Status::Ok();
}

void ExtendTracks(const TrackExtensionOptions& options, const Eigen::Vector2d& seen_min,
                  const Eigen::Vector2d& seen_max, Reconstruction* reconstruction,
                  TrackExtensionReport* report) {
  CHECK_EQ(reconstruction->world_T_base.size(), reconstruction->junctions.size());
  *report = TrackExtensionReport();
  Extender(reconstruction->calibration.camera.K(), seen_min, seen_max, reconstruction->WorldTCamera(),
           reconstruction->junctions, options, &reconstruction->tracks, &reconstruction->landmarks, report)
      .Run();
}

}  // namespace sfm
