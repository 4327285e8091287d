#include "backend/triangulation/landmark_merge.h"

#include <glog/logging.h>

#include <map>
#include <set>
#include <tuple>
#include <vector>

namespace sfm {

void MergeRetriangulatedLandmarks(const Landmarks& retriangulated, RetriangulatedLandmarks which,
                                  Landmarks* landmarks, LandmarkMergeReport* report) {
  CHECK(landmarks != nullptr);
  const int fresh_points = static_cast<int>(retriangulated.points.size());
  for (const LineLandmark& line : retriangulated.lines) {
    CHECK(line.point_landmark >= -1 && line.point_landmark < fresh_points)
        << "point_landmark " << line.point_landmark << " of " << fresh_points << " points";
  }
  LandmarkMergeReport merged;
  if (which == RetriangulatedLandmarks::kReplace) {
    *landmarks = retriangulated;
    merged.points_added = fresh_points;
    merged.lines_added = static_cast<int>(retriangulated.lines.size());
    if (report != nullptr) *report = merged;
    return;
  }

  // Track -> index of its point in the joined map.
  std::map<int, int> point_of_track;
  for (size_t i = 0; i < landmarks->points.size(); ++i) {
    point_of_track.emplace(landmarks->points[i].track_id, static_cast<int>(i));
  }
  // Retriangulated point index -> joined index (-1 until known).
  std::vector<int> joined_index(fresh_points, -1);
  for (int i = 0; i < fresh_points; ++i) {
    const PointLandmark& point = retriangulated.points[i];
    const auto found = point_of_track.find(point.track_id);
    if (found != point_of_track.end()) {
      joined_index[i] = found->second;
      continue;
    }
    joined_index[i] = static_cast<int>(landmarks->points.size());
    point_of_track.emplace(point.track_id, joined_index[i]);
    landmarks->points.push_back(point);
    ++merged.points_added;
  }

  // A segment track's views are distinct (frame, junction, segment) triples, and a triple belongs to
  // one segment track only: one shared triple means the same segment track.
  using Key = std::tuple<int, int, int>;
  std::set<Key> observed;
  for (const LineLandmark& line : landmarks->lines) {
    for (const LineObservation& o : line.observations) observed.emplace(o.frame, o.junction, o.segment);
  }
  const int existing_points = static_cast<int>(landmarks->points.size()) - merged.points_added;
  for (const LineLandmark& line : retriangulated.lines) {
    bool known = false;
    for (const LineObservation& o : line.observations)
      known = known || observed.count({o.frame, o.junction, o.segment});
    if (known) continue;
    LineLandmark added = line;
    added.point_landmark = line.point_landmark >= 0 ? joined_index[line.point_landmark] : -1;
    if (added.point_landmark >= 0 && added.point_landmark < existing_points) {
      added.end0 = landmarks->points[added.point_landmark].position;
      ++merged.lines_linked_to_existing_point;
    }
    landmarks->lines.push_back(std::move(added));
    ++merged.lines_added;
  }
  if (report != nullptr) *report = merged;
}

}  // namespace sfm
