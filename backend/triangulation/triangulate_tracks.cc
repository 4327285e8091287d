#include "backend/triangulation/triangulate_tracks.h"

#include <glog/logging.h>

#include <algorithm>
#include <unordered_set>

#include "frontend/junctions/location_information.h"

namespace sfm {

int TriangulationReport::Count(PointStatus status) const {
  return static_cast<int>(std::count(point_status.begin(), point_status.end(), status));
}

int TriangulationReport::Count(LineStatus status) const {
  int count = 0;
  for (const std::vector<LineStatus>& statuses : line_status) {
    count += static_cast<int>(std::count(statuses.begin(), statuses.end(), status));
  }
  return count;
}

bool SeenAsTOrX(const std::vector<Junctions>& junctions, const PointLandmark& point) {
  for (const PointObservation& observation : point.observations) {
    CHECK(observation.frame >= 0 && observation.frame < static_cast<int>(junctions.size()))
        << observation.frame;
    const Junctions& frame = junctions[observation.frame];
    CHECK(observation.junction >= 0 && observation.junction < static_cast<int>(frame.size()))
        << observation.junction;
    const JunctionType type = frame[observation.junction].type;
    if (type == JunctionType::kT || type == JunctionType::kX) return true;
  }
  return false;
}

void MarkOcclusionCandidates(const std::vector<Junctions>& junctions, Landmarks* landmarks) {
  for (PointLandmark& point : landmarks->points) point.occlusion_candidate = SeenAsTOrX(junctions, point);
}

namespace {

// The track's junction locations with their frames' poses, and as point observations (the
// track's views must index frames, CHECKed).
void TrackPointViews(const std::vector<Pose3>& world_T_camera, const std::vector<Junctions>& frames,
                     const JunctionTrack& track, std::vector<PointView>* views,
                     std::vector<PointObservation>* observations) {
  for (const TrackView& view : track.views) {
    CHECK(view.frame >= 0 && view.frame < static_cast<int>(frames.size()) && view.junction >= 0 &&
          view.junction < static_cast<int>(frames[view.frame].size()))
        << "track " << track.id << " views junction " << view.junction << " of frame " << view.frame;
    const Junction& junction = frames[view.frame][view.junction];
    views->push_back({world_T_camera[view.frame], junction.location});
    observations->push_back(
        {view.frame, view.junction, junction.location, LocationSqrtInformation(junction)});
  }
}

}  // namespace

Landmarks TriangulateTracks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                            const std::vector<Junctions>& frames, const std::vector<JunctionTrack>& tracks,
                            const TriangulationOptions& options, TriangulationReport* report) {
  CHECK(options.Check().ok()) << options.Check().message();
  CHECK_EQ(world_T_camera.size(), frames.size()) << "one camera pose per frame";
  Landmarks landmarks;
  TriangulationReport statuses;
  for (const JunctionTrack& track : tracks) {
    std::vector<PointView> point_views;
    std::vector<PointObservation> point_observations;
    TrackPointViews(world_T_camera, frames, track, &point_views, &point_observations);
    Eigen::Vector3d position;
    const PointStatus point_status = TriangulatePoint(K, point_views, options.point, &position);
    statuses.point_status.push_back(point_status);
    int point_index = -1;
    if (point_status == PointStatus::kOk) {
      point_index = static_cast<int>(landmarks.points.size());
      landmarks.points.push_back({track.id, position, point_observations});
      landmarks.points.back().occlusion_candidate = SeenAsTOrX(frames, landmarks.points.back());
    }

    statuses.line_status.emplace_back();
    for (int s = 0; s < track.NumSegments(); ++s) {
      std::vector<LineView> line_views;
      std::vector<LineObservation> line_observations;
      for (const TrackView& view : track.views) {
        const Junction& junction = frames[view.frame][view.junction];
        const int segment = view.segments[s];
        if (segment < 0)
          continue;  // this view's junction has no segment in this segment track (a partial match)
        CHECK(segment < junction.NumSegments()) << "track " << track.id << " segment " << segment;
        line_views.push_back({world_T_camera[view.frame], junction.location, junction.segments[segment].end});
        line_observations.push_back(
            {view.frame, view.junction, segment, junction.location, junction.segments[segment].end});
      }
      Line3 line;
      Segment3 segment;
      LineStatus line_status = TriangulateLine(K, line_views, options.line, &line);
      if (line_status == LineStatus::kOk) {
        line_status =
            BoundLine(K, line_views, line, point_index >= 0 ? &position : nullptr, options.line, &segment);
      }
      statuses.line_status.back().push_back(line_status);
      if (line_status != LineStatus::kOk) continue;
      LineLandmark landmark;
      landmark.point = segment.end0;
      landmark.direction = (segment.end1 - segment.end0).normalized();
      landmark.end0 = segment.end0;
      landmark.end1 = segment.end1;
      landmark.point_landmark = point_index;
      landmark.observations = std::move(line_observations);
      landmarks.lines.push_back(std::move(landmark));
    }
  }
  if (report != nullptr) *report = std::move(statuses);
  return landmarks;
}

int TriangulateMissingPoints(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                             const std::vector<Junctions>& frames, const std::vector<JunctionTrack>& tracks,
                             const PointTriangulationOptions& options, Landmarks* landmarks) {
  std::unordered_set<int> with_point;
  for (const PointLandmark& point : landmarks->points) with_point.insert(point.track_id);
  int added = 0;
  for (const JunctionTrack& track : tracks) {
    if (with_point.count(track.id) > 0) continue;
    std::vector<PointView> views;
    std::vector<PointObservation> observations;
    TrackPointViews(world_T_camera, frames, track, &views, &observations);
    Eigen::Vector3d position;
    if (TriangulatePoint(K, views, options, &position) != PointStatus::kOk) continue;
    landmarks->points.push_back({track.id, position, observations});
    landmarks->points.back().occlusion_candidate = SeenAsTOrX(frames, landmarks->points.back());
    ++added;
  }
  return added;
}

}  // namespace sfm
