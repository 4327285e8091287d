#include "backend/triangulation/wireframe_selection.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/line_triangulation.h"

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Callers first make sure there is something to test (degrees_of_freedom >= 1).
bool PassesChiSquare(double statistic, int degrees_of_freedom, double level) {
  return statistic <= ChiSquareQuantile(level, degrees_of_freedom);
}

double SmallestDepth(const std::vector<Pose3>& cameras, const Eigen::Vector3d& x) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Pose3& camera : cameras) smallest = std::min(smallest, (camera.Inverse() * x).z());
  return smallest;
}

// The line's extent measured again on `cameras` (the final poses) by BoundLine's rule: end0 at
// `junction_point` projected onto the line when there is one, else the median of the
// back-projected junction locations; end1 the median of the back-projected far ends. The
// landmark's own ends were bounded on the poses it was triangulated with (the odometry's) and
// bundle adjustment only slides them onto the refined line, so a pose correction of a few
// centimetres along the line stays in them. False when no segment of positive length in front of
// every camera results. The depth floor is not applied again (min_depth_m 0): the triangulation
// applied it.
bool BoundOnFinalPoses(const Eigen::Matrix3d& K, const std::vector<LineView>& views, const LineLandmark& line,
                       const Eigen::Vector3d* junction_point, Segment3* segment) {
  LineTriangulationOptions options;
  options.min_depth_m = 0;
  return BoundLine(K, views, Line3{line.point, line.direction}, junction_point, options, segment) == LineStatus::kOk;
}

}  // namespace

double MaxVertexSigma(const WireframeOptions& options, double fx, double depth) {
  return std::sqrt(2.0) * options.pixel_sigma_px / fx * depth /
         std::tan(options.min_equivalent_parallax_deg * kPi / 180);
}

PoseDrift WireframePoseDrift(const WireframeOptions& options, const std::vector<Pose3>& world_T_camera) {
  std::vector<double> steps;
  for (size_t f = 1; f < world_T_camera.size(); ++f) {
    steps.push_back((world_T_camera[f].translation - world_T_camera[f - 1].translation).norm());
  }
  double median_step = 0;
  if (!steps.empty()) {
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
    median_step = steps[steps.size() / 2];
  }
  return PoseDrift{options.pose_rotation_step_rad, options.pose_translation_step_fraction * median_step};
}

double EstimatePixelSigma(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const Landmarks& landmarks) {
  std::vector<double> components;
  for (const PointLandmark& point : landmarks.points) {
    for (const PointObservation& observation : point.observations) {
      CHECK(observation.frame >= 0 && observation.frame < static_cast<int>(world_T_camera.size()))
          << "frame " << observation.frame;
      const Eigen::Vector3d in_camera = world_T_camera[observation.frame].Inverse() * point.position;
      if (!(in_camera.z() > 0)) continue;
      const Eigen::Vector3d projected = K * in_camera;
      const Eigen::Vector2d residual = projected.hnormalized() - observation.pixel;
      components.push_back(std::abs(residual.x()));
      components.push_back(std::abs(residual.y()));
    }
  }
  if (components.empty()) return 0;
  auto middle = components.begin() + components.size() / 2;
  std::nth_element(components.begin(), middle, components.end());
  return 1.4826 * *middle;  // the median absolute deviation of a zero-mean Gaussian is 0.6745 sigma
}

Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const WireframeOptions& options,
                                   WireframeSelectionReport* report) {
  return SelectWireframeLandmarks(K, world_T_camera, landmarks, std::vector<Junctions>(), options, report);
}

Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const std::vector<Junctions>& junctions,
                                   const WireframeOptions& options, WireframeSelectionReport* report) {
  return SelectWireframeLandmarks(K, world_T_camera, landmarks, junctions, options,
                                  WireframePoseDrift(options, world_T_camera), report);
}

Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const std::vector<Junctions>& junctions,
                                   const WireframeOptions& options, const PoseDrift& drift,
                                   WireframeSelectionReport* report) {
  CHECK(options.Check().ok()) << options.Check().message();
  const double sigma_px =
      options.estimate_pixel_sigma
          ? std::max(options.pixel_sigma_px, EstimatePixelSigma(K, world_T_camera, landmarks))
          : options.pixel_sigma_px;
  const double fx = K(0, 0);
  auto camera = [&world_T_camera](int frame) -> const Pose3& {
    CHECK(frame >= 0 && frame < static_cast<int>(world_T_camera.size())) << "frame " << frame;
    return world_T_camera[frame];
  };
  // A vertex is determined when its sigma is within the bound at its smallest depth (> 0). The
  // bound takes the same pixel noise as the sigma, so that the pixel part of the test does not
  // depend on the noise level (only the pose drift's share does).
  WireframeOptions bound_options = options;
  bound_options.pixel_sigma_px = sigma_px;
  auto determined = [&](double sigma, double depth) {
    return depth > 0 && sigma <= MaxVertexSigma(bound_options, fx, depth);
  };
  WireframeSelectionReport counts;
  Landmarks selected;
  std::vector<int> new_index(landmarks.points.size(), -1);
  for (size_t i = 0; i < landmarks.points.size(); ++i) {
    const PointLandmark& point = landmarks.points[i];
    std::vector<Pose3> cameras;
    std::vector<Eigen::Vector2d> pixels;
    std::vector<int> frames;
    for (const PointObservation& observation : point.observations) {
      cameras.push_back(camera(observation.frame));
      frames.push_back(observation.frame);
      pixels.push_back(observation.pixel);
    }
    int dof = 0;
    const double chi_square = PointChiSquare(K, cameras, pixels, point.position, sigma_px, &dof);
    if (dof < 1) {  // one view left (bundle adjustment removed the others): nothing to test
      ++counts.points_untestable;
      continue;
    }
    if (!PassesChiSquare(chi_square, dof, options.consistency_level)) {
      ++counts.points_inconsistent;
      continue;
    }
    if (!junctions.empty() && SeenAsTOrX(junctions, point) &&
        static_cast<int>(point.observations.size()) < options.occlusion_candidate_min_views) {
      ++counts.points_occlusion_untested;
      continue;
    }
    if (!determined(PointPositionSigma(K, cameras, frames, point.position, sigma_px, drift),
                    SmallestDepth(cameras, point.position))) {
      ++counts.points_uncertain;
      continue;
    }
    new_index[i] = static_cast<int>(selected.points.size());
    selected.points.push_back(point);
  }
  for (const LineLandmark& line : landmarks.lines) {
    std::vector<LineSegmentView> views;
    std::vector<LineView> line_views;
    std::vector<Pose3> cameras;
    for (const LineObservation& observation : line.observations) {
      views.push_back({camera(observation.frame), observation.p0, observation.p1, observation.frame});
      line_views.push_back({camera(observation.frame), observation.p0, observation.p1});
      cameras.push_back(camera(observation.frame));
    }
    int dof = 0;
    const double chi_square = LineChiSquare(K, views, line.point, line.direction, sigma_px, &dof);
    // Two views of a line always meet in one (their planes intersect): a track that pairs two
    // different edges passes an empty test. Only tested tracks are drawn: a two-view line only
    // when its junction point was kept, i.e. the junction correspondence passed the point's test
    // (1 degree of freedom, the epipolar constraint); the matcher pairs a junction's segments
    // with its location (one shift for all of them). A two-view T or X is not kept: its location
    // need not be one 3D point even when matched right, so its test checks no correspondence.
    if (dof < 1 && (line.point_landmark < 0 || new_index[line.point_landmark] < 0)) {
      ++counts.lines_untestable;
      continue;
    }
    if (dof >= 1 && !PassesChiSquare(chi_square, dof, options.consistency_level)) {
      ++counts.lines_inconsistent;
      continue;
    }
    LineLandmark kept = line;
    kept.point_landmark = line.point_landmark >= 0 ? new_index[line.point_landmark] : -1;
    // A dropped point is not the line's end (it may lie off the line): the line's own junction
    // end is used instead.
    const Eigen::Vector3d* junction_point =
        kept.point_landmark >= 0 ? &landmarks.points[line.point_landmark].position : nullptr;
    Segment3 segment;
    if (!BoundOnFinalPoses(K, line_views, line, junction_point, &segment)) {
      ++counts.lines_unbounded;
      continue;
    }
    kept.direction = (segment.end1 - segment.end0).normalized();
    kept.end0 = kept.point_landmark >= 0 ? line.end0 : segment.end0;
    kept.end1 = segment.end1;
    if (kept.point_landmark < 0 &&
        !determined(LinePositionSigma(K, views, kept.end0, kept.direction, sigma_px, drift,
                                      options.line_sigma_subtracts_plane_noise),
                    SmallestDepth(cameras, kept.end0))) {
      ++counts.lines_uncertain_end0;
      continue;
    }
    if (!determined(LinePositionSigma(K, views, kept.end1, kept.direction, sigma_px, drift,
                                      options.line_sigma_subtracts_plane_noise),
                    SmallestDepth(cameras, kept.end1))) {
      ++counts.lines_uncertain_end1;
      continue;
    }
    selected.lines.push_back(std::move(kept));
  }
  counts.pixel_sigma_px = sigma_px;
  counts.points_kept = static_cast<int>(selected.points.size());
  counts.lines_kept = static_cast<int>(selected.lines.size());
  if (report != nullptr) *report = counts;
  return selected;
}

}  // namespace sfm
