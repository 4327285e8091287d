// The landmarks the wireframe shows: those whose observations agree with them (a chi-square test
// of the residuals at the pixel noise) and whose vertices the views determine well enough (the
// first-order position uncertainty against a relative bound), judged on the final (refined) poses.
// Bundle adjustment keeps using every landmark: an imprecise distant point still fixes rotation.
// docs/tracks_and_triangulation.md, "Wireframe vertices".
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/landmarks.h"
#include "backend/triangulation/triangulate_tracks.h"
#include "backend/triangulation/triangulation_options.h"
#include "geometry/pose.h"
#include "frontend/junctions/junction.h"

namespace sfm {

struct WireframeSelectionReport {
  int points_untestable = 0;      // fewer than two views: no redundancy to test
  int points_occlusion_untested = 0;  // a T or X (occlusion candidate) with too few views to test it
  int points_inconsistent = 0;    // point residuals fail the chi-square test
  int points_uncertain = 0;       // point position sigma above the bound
  int lines_untestable = 0;       // two views (nothing to test) and no kept junction point
  int lines_inconsistent = 0;     // line residuals fail the chi-square test
  int lines_uncertain_end0 = 0;   // the junction end (the line's own, or a dropped point's) too uncertain
  int lines_uncertain_end1 = 0;   // the far end too uncertain
  int lines_unbounded = 0;        // no extent of positive length in front of the cameras on the final poses
  int points_beyond_tolerance = 0;  // dropped by the accuracy asked (WireframeOptions::tolerance_m)
  int lines_beyond_tolerance = 0;   // the same, lines (with their own vertex, or their point's)
  double predicted_share = 0;       // the drawn vertices' predicted share within tolerance_m (0: off)
  int points_kept = 0, lines_kept = 0;
  int lines_far_end_at_point = 0;   // kept lines whose end1 is a drawn point (far_end_at_point_px)
  double pixel_sigma_px = 0;      // the noise the chi-square tests used
  // Set by the pipeline: the pose error model of the determination test ("random_walk" or
  // "bundle_adjustment"), and the seconds the bundle adjustment's pose covariance took (0 without).
  std::string pose_error_model = "random_walk";
  double pose_covariance_seconds = 0;
};

// The largest position sigma (metres) that WireframeOptions allows for a vertex whose smallest
// depth in a view that sees it is `depth`: sqrt(2) (pixel_sigma_px / fx) depth /
// tan(min_equivalent_parallax_deg).
double MaxVertexSigma(const WireframeOptions& options, double fx, double depth);

// The pixel noise seen in the points' observations: 1.4826 x the median absolute component of the
// reprojection residuals (x and y) of every point observation on world_T_camera (the scale of a
// Gaussian, robust to the few outliers left). 0 when there are no point observations in front of
// their cameras.
double EstimatePixelSigma(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const Landmarks& landmarks);

// The pose drift the selection adds to a vertex's sigma: options.pose_rotation_step_rad, and
// options.pose_translation_step_fraction times the median distance between consecutive camera
// centres of world_T_camera (0 with fewer than two cameras).
PoseDrift WireframePoseDrift(const WireframeOptions& options, const std::vector<Pose3>& world_T_camera);

// The subset of `landmarks` to draw, with the cameras world_T_camera[f] of every frame (the refined
// poses when bundle adjustment ran). A point is kept when it passes the test and its
// PointPositionSigma is within MaxVertexSigma of its smallest depth. A line is kept when its track
// was tested (three views or more and it passes its own test, or two views and its junction point
// kept), bounds a segment on these poses
// (BoundLine's rule: its stored ends were bounded on the triangulation's poses) and both its
// vertices are within the bound (LinePositionSigma at end1, and at end0 unless end0 is a kept
// point). A line whose point was dropped takes its own end0 (the median of its back-projected
// junction locations) and point_landmark -1; point_landmark is renumbered. Order is preserved.
// With options.far_end_at_point_px > 0 a kept line's end1 is then moved to a kept point that its
// observed image lines and far end-points agree with (end1_point_landmark set when
// far_end_shares_vertex).
// options must pass Check(), every observation must index world_T_camera (CHECKed).
Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const WireframeOptions& options,
                                   WireframeSelectionReport* report = nullptr);

// The same, knowing the junctions the observations index (junctions[frame][observation.junction],
// CHECKed): a point whose junction is a T or an X in any of its views (an occlusion candidate) is
// drawn only with options.occlusion_candidate_min_views views or more. Without them (the overload
// above) the junction types are unknown and that rule is not applied.
Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const std::vector<Junctions>& junctions,
                                   const WireframeOptions& options,
                                   WireframeSelectionReport* report = nullptr);

// The same with the pose error given (instead of WireframePoseDrift(options, world_T_camera)), e.g.
// PoseDrift::covariance from bundle adjustment (backend/bundle_adjustment/pose_covariance.h).
Landmarks SelectWireframeLandmarks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                                   const Landmarks& landmarks, const std::vector<Junctions>& junctions,
                                   const WireframeOptions& options, const PoseDrift& drift,
                                   WireframeSelectionReport* report = nullptr);

}  // namespace sfm
