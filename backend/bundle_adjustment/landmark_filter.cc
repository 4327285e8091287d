#include "backend/bundle_adjustment/landmark_filter.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/observability.h"
#include "backend/bundle_adjustment/point_reprojection_cost.h"

namespace sfm {
namespace {

bool Finite(const Eigen::Vector2d& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

// Removes the observations that `keep` rejects; returns how many.
template <typename Landmark, typename Keep>
int RemoveObservations(Landmark* landmark, Keep keep) {
  auto& observations = landmark->observations;
  const size_t before = observations.size();
  observations.erase(std::remove_if(observations.begin(), observations.end(),
                                    [&keep](const auto& observation) { return !keep(observation); }),
                     observations.end());
  return static_cast<int>(before - observations.size());
}

std::vector<Eigen::Vector3d> Centres(const std::vector<Pose3>& cameras) {
  std::vector<Eigen::Vector3d> centres;
  for (const Pose3& camera : cameras) centres.push_back(camera.translation);
  return centres;
}

}  // namespace

bool LandmarkFilter::PointResiduals(const PointLandmark& point, const PointObservation& observation,
                                    Eigen::Vector2d* r, bool whitened) const {
  const PoseParameters& pose = parameters_.poses[observation.frame];
  return PointReprojectionCost(setup_.camera, observation.pixel,
                               whitened ? observation.sqrt_information : Eigen::Matrix2d::Identity())(
             pose.rotation.data(), pose.translation.data(), point.position.data(), r->data()) &&
         Finite(*r);
}
bool LandmarkFilter::LineResiduals(const OrthonormalLine& line, const LineObservation& observation,
                                   Eigen::Vector2d* r) const {
  const PoseParameters& pose = parameters_.poses[observation.frame];
  return LineReprojectionCost(setup_.camera, observation.p0, observation.p1)(
             pose.rotation.data(), pose.translation.data(), line.data(), r->data()) &&
         Finite(*r);
}

int LandmarkFilter::CountObservations() const {
  int count = 0;
  for (const PointLandmark& point : landmarks_->points) count += static_cast<int>(point.observations.size());
  for (const LineLandmark& line : landmarks_->lines) count += static_cast<int>(line.observations.size());
  return count;
}

void LandmarkFilter::DropUnusableObservations() {
  Eigen::Vector2d r;
  for (PointLandmark& point : landmarks_->points) {
    summary_->observations_unusable += RemoveObservations(
        &point, [&](const PointObservation& observation) { return PointResiduals(point, observation, &r); });
  }
  for (LineLandmark& line : landmarks_->lines) {
    const OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
    summary_->observations_unusable += RemoveObservations(&line, [&](const LineObservation& observation) {
      return LineResiduals(parameters, observation, &r);
    });
  }
}

// Removes the landmarks that `keep_point` / `keep_line` reject, renumbering point_landmark.
// Returns the numbers of points and lines removed.
template <typename KeepPoint, typename KeepLine>
std::pair<int, int> LandmarkFilter::RemoveLandmarks(KeepPoint keep_point, KeepLine keep_line) {
  std::vector<PointLandmark>& points = landmarks_->points;
  std::vector<int> new_index(points.size(), -1);
  size_t kept = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!keep_point(points[i])) continue;
    new_index[i] = static_cast<int>(kept);
    if (kept != i) points[kept] = std::move(points[i]);
    ++kept;
  }
  const int points_removed = static_cast<int>(points.size() - kept);
  points.resize(kept);
  std::vector<LineLandmark>& lines = landmarks_->lines;
  const size_t lines_before = lines.size();
  lines.erase(
      std::remove_if(lines.begin(), lines.end(), [&](const LineLandmark& line) { return !keep_line(line); }),
      lines.end());
  for (LineLandmark& line : lines) {
    if (line.point_landmark >= 0) line.point_landmark = new_index[line.point_landmark];
  }
  return {points_removed, static_cast<int>(lines_before - lines.size())};
}

void LandmarkFilter::RemoveLandmarksWithFewViews() {
  const auto [points, lines] =
      RemoveLandmarks([](const PointLandmark& point) { return point.observations.size() >= 2; },
                      [](const LineLandmark& line) { return line.observations.size() >= 2; });
  summary_->points_removed += points;
  summary_->lines_removed += lines;
}

template <typename Observations>
std::vector<Pose3> LandmarkFilter::CameraPoses(const Observations& observations) const {
  std::vector<Pose3> cameras;
  for (const auto& observation : observations) {
    cameras.push_back(parameters_.poses[observation.frame].ToPose() * setup_.base_T_camera);
  }
  return cameras;
}

// Returns the number of landmarks dropped. `refined`: the landmarks and poses have been solved
// for, so the depth floor applies too. Not before the first solve: landmarks triangulated on
// drifting odometry can start within min_depth_m of a camera (or behind it) and be fine after
// it (the triangulation already held them to the floor on the odometry's poses).
int LandmarkFilter::DropUnobservableLandmarks(bool refined) {
  const auto [points, lines] = RemoveLandmarks(
      [&](const PointLandmark& point) {
        const std::vector<Pose3> cameras = CameraPoses(point.observations);
        return (!refined || SmallestDepth({point.position}, cameras) >= setup_.options.min_depth_m) &&
               PointTriangulationAngleDeg(point.position, Centres(cameras)) >=
                   setup_.options.min_point_triangulation_angle_deg;
      },
      [&](const LineLandmark& line) {
        const std::vector<Pose3> cameras = CameraPoses(line.observations);
        for (size_t i = 0; refined && i < cameras.size(); ++i) {
          const LineObservation& observation = line.observations[i];
          if (!(ObservedLineDepth(setup_.K, cameras[i], observation.p0, observation.p1, line.point,
                                  line.direction) >= setup_.options.min_depth_m)) {
            return false;
          }
        }
        // The estimate of a degenerate line can be anywhere (its triangulation has no unique
        // solution), so the planes of its image lines must also meet at a large enough angle.
        std::vector<Eigen::Vector3d> normals;
        for (size_t i = 0; i < line.observations.size(); ++i) {
          const LineObservation& observation = line.observations[i];
          normals.push_back(BackProjectedPlaneNormal(setup_.K, cameras[i].RotationMatrix(), observation.p0,
                                                     observation.p1));
        }
        const double angle_deg =
            std::min(LineTriangulationAngleDeg(line.point, line.direction, Centres(cameras)),
                     LargestPlaneAngleDeg(normals));
        return angle_deg >= setup_.options.min_line_triangulation_angle_deg;
      });
  summary_->points_unobservable += points;
  summary_->lines_unobservable += lines;
  return points + lines;
}

int LandmarkFilter::RemoveOutliers(double threshold_px) {
  Eigen::Vector2d r;
  int removed = 0;
  for (PointLandmark& point : landmarks_->points) {
    removed += RemoveObservations(&point, [&](const PointObservation& observation) {
      return PointResiduals(point, observation, &r) && r.norm() <= threshold_px;
    });
  }
  for (LineLandmark& line : landmarks_->lines) {
    const OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
    removed += RemoveObservations(&line, [&](const LineObservation& observation) {
      return LineResiduals(parameters, observation, &r) && r.norm() <= threshold_px;
    });
  }
  summary_->observations_removed += removed;
  return removed;
}

void LandmarkFilter::ComputeRms() {
  Eigen::Vector2d r;
  double point_sum = 0, line_sum = 0;
  int point_count = 0, line_count = 0;
  for (const PointLandmark& point : landmarks_->points) {
    for (const PointObservation& observation : point.observations) {
      if (!PointResiduals(point, observation, &r, /*whitened=*/false)) continue;
      point_sum += r.squaredNorm();
      ++point_count;
    }
  }
  for (const LineLandmark& line : landmarks_->lines) {
    const OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
    for (const LineObservation& observation : line.observations) {
      if (!LineResiduals(parameters, observation, &r)) continue;
      line_sum += r.squaredNorm();
      line_count += 2;  // two end-points
    }
  }
  summary_->point_rms_px = point_count > 0 ? std::sqrt(point_sum / point_count) : 0;
  summary_->line_rms_px = line_count > 0 ? std::sqrt(line_sum / line_count) : 0;
}

}  // namespace sfm
